#include "app/render/tev_display.h"

#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <type_traits>

#include "core/limits/error.h"

namespace rtiow {
namespace {

// How long a viewer may take to accept the connection, and to take one packet.
constexpr int kConnectMilliseconds = 3000;
constexpr int kSendSeconds = 5;
// Pixels a packet carries at most (tev's packets hold their size in 32 bits).
constexpr std::size_t kPacketFloats = std::size_t(4) << 20;

// tev's packet types (its IpcPacket::EType).
constexpr char kCreateImage = 4;
constexpr char kUpdateImageV3 = 6;

// A packet as tev reads it: its size (32 bits, little-endian, itself included), its type,
// then the fields: booleans as a byte, strings ending in a zero byte, integers and floats
// little-endian.
class Packet {
 public:
  explicit Packet(char type) : bytes_(4, '\0') { bytes_.push_back(type); }
  Packet& flag(bool value) {
    bytes_.push_back(value ? '\1' : '\0');
    return *this;
  }
  Packet& text(const std::string& value) {
    bytes_.append(value).push_back('\0');
    return *this;
  }
  template <typename Int>
  Packet& integer(Int value) {
    const auto bits = static_cast<std::make_unsigned_t<Int>>(value);
    for (std::size_t i = 0; i < sizeof(Int); ++i) bytes_.push_back(char((bits >> (8 * i)) & 0xff));
    return *this;
  }
  Packet& number(float value) {
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return integer(bits);
  }
  std::string done() {
    const auto size = std::uint32_t(bytes_.size());
    for (std::size_t i = 0; i < 4; ++i) bytes_[i] = char((size >> (8 * i)) & 0xff);
    return std::move(bytes_);
  }

 private:
  std::string bytes_;
};

// A connected socket to `address` within kConnectMilliseconds, or -1 with `why` set.
int connect_to(const DisplayAddress& address, std::string& why) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  if (const int error = ::getaddrinfo(address.host.c_str(), address.port.c_str(), &hints, &found);
      error != 0) {
    why = std::string("cannot find it: ") + ::gai_strerror(error);
    return -1;
  }
  int connected = -1;
  why = "no address to connect to";
  for (const addrinfo* a = found; a && connected < 0; a = a->ai_next) {
    const int fd =
        ::socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) {
      why = system_error_text(errno);
      continue;
    }
    int error = ::connect(fd, a->ai_addr, a->ai_addrlen) == 0 ? 0 : errno;
    if (error == EINPROGRESS) {
      pollfd ready{fd, POLLOUT, 0};
      const int polled = ::poll(&ready, 1, kConnectMilliseconds);
      socklen_t length = sizeof error;
      if (polled == 0) {
        error = ETIMEDOUT;
      } else if (polled < 0 || ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &length) != 0) {
        error = errno;
      }
    }
    if (error != 0) {
      why = "cannot connect: " + system_error_text(error);
      ::close(fd);
      continue;
    }
    // Blocking from here on, but never for long: a viewer that stops reading ends the display.
    const timeval limit{kSendSeconds, 0};
    ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &limit, sizeof limit);
    (void)::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    connected = fd;
  }
  ::freeaddrinfo(found);
  return connected;
}

}  // namespace

DisplayAddress parse_display_address(const std::string& text) {
  DisplayAddress address;
  std::string rest;
  if (!text.empty() && text.front() == '[') {  // [IPV6] or [IPV6]:PORT
    const std::size_t close = text.find(']');
    if (close == std::string::npos) {
      throw InvalidInput("--display " + quote_value(text) + ": an IPv6 address ends with ']'");
    }
    address.host = text.substr(1, close - 1);
    rest = text.substr(close + 1);
    if (!rest.empty() && rest.front() != ':') {
      throw InvalidInput("--display " + quote_value(text) + ": expected HOST:PORT");
    }
    address.port = rest.empty() ? kTevDefaultPort : rest.substr(1);
  } else {
    const std::size_t colon = text.rfind(':');
    address.host = text.substr(0, colon);
    address.port = colon == std::string::npos ? kTevDefaultPort : text.substr(colon + 1);
  }
  const bool digits = !address.port.empty() && address.port.size() <= 5 &&
                      std::all_of(address.port.begin(), address.port.end(),
                                  [](char c) { return c >= '0' && c <= '9'; });
  // "14158" alone is a port, not the host 0.0.55.78 the resolver would make of it.
  if (!address.host.empty() && address.host.find_first_not_of("0123456789") == std::string::npos) {
    throw InvalidInput("--display " + quote_value(text) +
                       ": a number alone is not a host; give HOST:PORT (tev listens on "
                       "127.0.0.1:14158)");
  }
  if (address.host.empty() || !digits || std::stoi(address.port) < 1 ||
      std::stoi(address.port) > 65535) {
    throw InvalidInput("--display " + quote_value(text) +
                       ": expected HOST:PORT (tev listens on 127.0.0.1:14158), a port from 1 to "
                       "65535");
  }
  return address;
}

TevDisplay::TevDisplay(const DisplayAddress& address, std::string name, int film_width,
                       int film_height, const FramePlacement& placement,
                       std::vector<std::string> extra)
    : where_(address.host + ":" + address.port),
      name_(std::move(name)),
      placement_(placement),
      channels_{"R", "G", "B"} {
  channels_.insert(channels_.end(), extra.begin(), extra.end());
  std::string why;
  socket_ = connect_to(address, why);
  if (socket_ < 0) {
    fail(why);
    return;
  }
  const int width = placement.whole() ? film_width : placement.frame_width;
  const int height = placement.whole() ? film_height : placement.frame_height;
  Packet create(kCreateImage);
  create.flag(false).text(name_).integer(std::int32_t(width)).integer(std::int32_t(height));
  create.integer(std::int32_t(channels_.size()));
  for (const std::string& channel : channels_) create.text(channel);
  send_packet(create.done());
}

TevDisplay::~TevDisplay() {
  if (socket_ >= 0) ::close(socket_);
}

void TevDisplay::fail(const std::string& why) {
  std::fprintf(stderr, "rtiow: warning: --display %s: %s; the render goes on without it\n",
               quote_value(where_).c_str(), one_line(why).c_str());
  if (socket_ >= 0) ::close(socket_);
  socket_ = -1;
}

bool TevDisplay::send_packet(const std::string& packet) {
  for (std::size_t sent = 0; sent < packet.size();) {
    const ssize_t n = ::send(socket_, packet.data() + sent, packet.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      fail(n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)
               ? "the viewer took no pixels for " + std::to_string(kSendSeconds) + " s"
               : "the connection ended: " + system_error_text(n < 0 ? errno : EPIPE));
      return false;
    }
    sent += std::size_t(n);
  }
  return true;
}

void TevDisplay::show(const Film& film, const std::vector<ExtraChannel>& extra) {
  if (socket_ < 0 || film.width() < 1) return;
  // The channels created, every time: an update of fewer would leave tev's others stale.
  if (extra.size() + 3 != channels_.size()) return;
  // In strips of rows, the channels interleaved (channel c at offset c, stride their count).
  const std::size_t count = channels_.size();
  const std::size_t row_floats = std::size_t(film.width()) * count;
  const int rows = int(std::max<std::size_t>(1, kPacketFloats / row_floats));
  for (int y0 = 0; y0 < film.height(); y0 += rows) {
    const int strip = std::min(rows, film.height() - y0);
    Packet update(kUpdateImageV3);
    update.flag(false).text(name_).integer(std::int32_t(count));
    for (const std::string& channel : channels_) update.text(channel);
    update.integer(std::int32_t(placement_.x)).integer(std::int32_t(placement_.y + y0));
    update.integer(std::int32_t(film.width())).integer(std::int32_t(strip));
    for (std::size_t c = 0; c < count; ++c) update.integer(std::int64_t(c));
    for (std::size_t c = 0; c < count; ++c) update.integer(std::int64_t(count));
    for (int y = y0; y < y0 + strip; ++y) {
      for (int x = 0; x < film.width(); ++x) {
        const Color& c = film.at(x, y);
        update.number(c.x).number(c.y).number(c.z);
        const std::size_t p = std::size_t(y) * std::size_t(film.width()) + std::size_t(x);
        for (const ExtraChannel& channel : extra) update.number(channel.values[p]);
      }
    }
    if (!send_packet(update.done())) return;
  }
}

}  // namespace rtiow
