#include "core/session/tev_display.h"

#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <pthread.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <optional>
#include <string>
#include <system_error>
#include <thread>

#include "core/limits/error.h"
#include "core/limits/setting_name.h"
#include "core/render/stopwatch.h"
#include "core/session/tev_packet.h"

namespace rtiow {
namespace {

// Floats a packet carries at most (tev's packets hold their size in 32 bits).
constexpr std::size_t kPacketFloats = std::size_t(4) << 20;

constexpr auto kViewerTime = std::chrono::seconds(kViewerSeconds);

std::string display_setting(const std::string& where) {
  return setting("display") + " " + quote_value(where);
}

}  // namespace

struct TevDisplay::Link {
  // A picture as it goes out: every pixel's channels side by side (R, G, B, then the extra ones).
  struct Picture {
    int width = 0, height = 0;
    std::vector<float> values;
  };

  // Fixed before the thread starts.
  DisplayAddress address;
  std::string where, name;
  FramePlacement placement;
  int frame_width = 0, frame_height = 0;
  std::vector<std::string> channels;    // R, G, B, then the extra ones
  int wake_read = -1, wake_write = -1;  // a pipe: a byte in it ends the thread's waits
  std::thread thread;

  std::mutex mutex;
  std::condition_variable changed;
  // Under the mutex.
  std::optional<Picture> pending;  // handed over, not yet taken by the thread
  bool sending = false;            // the thread is sending a picture
  bool resolving = false;          // the thread is in the resolver, which nothing interrupts
  bool closing = false;            // the owner ends the thread
  bool ended = false;              // the thread is done: the viewer dropped, or closing
  bool silent = false;             // a warning given, or the owner gone: say nothing more

  ~Link() {
    for (int fd : {wake_read, wake_write}) {
      if (fd >= 0) ::close(fd);
    }
  }

  // The one warning, unless one was given or the owner is gone.
  void warn(const std::string& why, const char* then = "the render goes on without it") {
    if (silent) return;
    silent = true;
    std::fprintf(stderr, "rtiow: warning: %s: %s; %s\n", display_setting(where).c_str(),
                 one_line(why).c_str(), then);
  }
  void drop(const std::string& why) {
    const std::lock_guard lock(mutex);
    if (!closing) warn(why);
    ended = true;
    pending.reset();
    changed.notify_all();
  }
};

namespace {

using Link = TevDisplay::Link;
using Picture = Link::Picture;

// How a wait for the socket ended.
enum class Waited { Ready, Closing, TimedOut };

// Waits until `fd` has `events` or the owner wakes the thread, at most until `deadline`.
Waited wait_for(Link& link, int fd, short events, Clock::time_point deadline) {
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) return Waited::TimedOut;
    pollfd fds[2] = {{fd, events, 0}, {link.wake_read, POLLIN, 0}};
    const int polled = ::poll(fds, 2, int(std::min<long long>(left, 1000)));
    if (polled < 0 && errno != EINTR) return Waited::Ready;  // the send says what is wrong
    if (fds[1].revents != 0) return Waited::Closing;
    if (polled > 0 && fds[0].revents != 0) return Waited::Ready;
  }
}

// The host's addresses, unless the owner closed meanwhile (then null, no warning). The resolver
// cannot be interrupted: while it runs, the owner may leave this thread behind.
addrinfo* resolve(Link& link, std::string& why) {
  {
    const std::lock_guard lock(link.mutex);
    if (link.closing) return nullptr;
    link.resolving = true;
  }
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  const int error =
      ::getaddrinfo(link.address.host.c_str(), link.address.port.c_str(), &hints, &found);
  const std::lock_guard lock(link.mutex);
  link.resolving = false;
  if (error != 0) {
    why = std::string("cannot find it: ") + ::gai_strerror(error);
    return nullptr;
  }
  if (link.closing) {
    ::freeaddrinfo(found);
    return nullptr;
  }
  return found;
}

// A connected, non-blocking socket to the viewer by `deadline`, or -1 with `why` set (empty when
// the owner closed).
int connect_to(Link& link, Clock::time_point deadline, std::string& why) {
  addrinfo* found = resolve(link, why);
  if (!found) return -1;
  if (Clock::now() >= deadline) {
    ::freeaddrinfo(found);
    why = "finding it took more than " + std::to_string(kViewerSeconds) + " s";
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
      const Waited waited = wait_for(link, fd, POLLOUT, deadline);
      socklen_t length = sizeof error;
      if (waited == Waited::Closing) {
        ::close(fd);
        why.clear();
        break;
      }
      if (waited == Waited::TimedOut) {
        error = ETIMEDOUT;
      } else if (::getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &length) != 0) {
        error = errno;
      }
    }
    if (error != 0) {
      why = "cannot connect: " + system_error_text(error);
      ::close(fd);
      continue;
    }
    connected = fd;
  }
  ::freeaddrinfo(found);
  return connected;
}

// Sends `bytes` by `deadline`; false with `why` set (empty when the owner closed) if not.
bool send_within(Link& link, int fd, const std::string& bytes, Clock::time_point deadline,
                 std::string& why) {
  for (std::size_t sent = 0; sent < bytes.size();) {
    const ssize_t n =
        ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n > 0) {
      sent += std::size_t(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      const Waited waited = wait_for(link, fd, POLLOUT, deadline);
      if (waited == Waited::Ready) continue;
      why = waited == Waited::Closing ? ""
                                      : "the viewer took more than " +
                                            std::to_string(kViewerSeconds) + " s over one picture";
      return false;
    }
    why = "the connection ended: " + system_error_text(n < 0 ? errno : EPIPE);
    return false;
  }
  return true;
}

std::string create_packet(const Link& link) {
  tev::Packet create(tev::kCreateImage);
  create.flag(false).text(link.name);
  create.integer(std::int32_t(link.frame_width)).integer(std::int32_t(link.frame_height));
  create.integer(std::int32_t(link.channels.size()));
  for (const std::string& channel : link.channels) create.text(channel);
  return create.done();
}

// Sends `picture` in strips of rows (each an update of every channel, interleaved: channel c at
// offset c, stride their count), all by `deadline`.
bool send_picture(Link& link, int fd, const Picture& picture, Clock::time_point deadline,
                  std::string& why) {
  const std::size_t count = link.channels.size();
  const std::size_t row_floats = std::size_t(picture.width) * count;
  const int rows = int(std::max<std::size_t>(1, kPacketFloats / row_floats));
  for (int y0 = 0; y0 < picture.height; y0 += rows) {
    const int strip = std::min(rows, picture.height - y0);
    tev::Packet update(tev::kUpdateImageV3);
    update.flag(false).text(link.name).integer(std::int32_t(count));
    for (const std::string& channel : link.channels) update.text(channel);
    update.integer(std::int32_t(link.placement.x)).integer(std::int32_t(link.placement.y + y0));
    update.integer(std::int32_t(picture.width)).integer(std::int32_t(strip));
    for (std::size_t c = 0; c < count; ++c) update.integer(std::int64_t(c));
    for (std::size_t c = 0; c < count; ++c) update.integer(std::int64_t(count));
    const std::size_t first = std::size_t(y0) * row_floats,
                      floats = std::size_t(strip) * row_floats;
    update.reserve(floats * sizeof(float));
    for (std::size_t i = first; i < first + floats; ++i) update.number(picture.values[i]);
    if (!send_within(link, fd, update.done(), deadline, why)) return false;
  }
  return true;
}

// The viewer's thread: connects, creates the image, then sends each picture handed over until the
// owner closes or the viewer is dropped. Signals are left to the render's threads.
void serve(const std::shared_ptr<Link>& held) {
  Link& link = *held;
  sigset_t all;
  sigfillset(&all);
  pthread_sigmask(SIG_BLOCK, &all, nullptr);
  std::string why;
  const int fd = connect_to(link, Clock::now() + kViewerTime, why);
  if (fd >= 0 && send_within(link, fd, create_packet(link), Clock::now() + kViewerTime, why)) {
    for (;;) {
      Picture picture;
      {
        std::unique_lock lock(link.mutex);
        link.changed.wait(lock, [&] { return link.pending || link.closing; });
        if (link.closing) break;
        picture = std::move(*link.pending);
        link.pending.reset();
        link.sending = true;
      }
      const bool sent = send_picture(link, fd, picture, Clock::now() + kViewerTime, why);
      {
        const std::lock_guard lock(link.mutex);
        link.sending = false;
        link.changed.notify_all();
      }
      if (!sent) break;
    }
  }
  if (fd >= 0) ::close(fd);
  link.drop(why);  // no warning when `why` is empty: the owner closed
}

}  // namespace

DisplayAddress parse_display_address(const std::string& text) {
  const std::string named = setting("display") + " " + quote_value(text);
  DisplayAddress address;
  std::string rest;
  if (!text.empty() && text.front() == '[') {  // [IPV6] or [IPV6]:PORT
    const std::size_t close = text.find(']');
    if (close == std::string::npos) throw InvalidInput(named + ": an IPv6 address ends with ']'");
    address.host = text.substr(1, close - 1);
    rest = text.substr(close + 1);
    if (!rest.empty() && rest.front() != ':') throw InvalidInput(named + ": expected HOST:PORT");
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
    throw InvalidInput(named +
                       ": a number alone is not a host; give HOST:PORT (tev listens on "
                       "127.0.0.1:14158)");
  }
  if (address.host.empty() || !digits || std::stoi(address.port) < 1 ||
      std::stoi(address.port) > 65535) {
    throw InvalidInput(named +
                       ": expected HOST:PORT (tev listens on 127.0.0.1:14158), a port from 1 to "
                       "65535");
  }
  return address;
}

TevDisplay::TevDisplay(const DisplayAddress& address, std::string name, int film_width,
                       int film_height, const FramePlacement& placement,
                       std::vector<std::string> extra)
    : link_(std::make_shared<Link>()) {
  Link& link = *link_;
  link.address = address;
  link.where = address.host + ":" + address.port;
  link.name = std::move(name);
  link.placement = placement;
  link.frame_width = placement.whole() ? film_width : placement.frame_width;
  link.frame_height = placement.whole() ? film_height : placement.frame_height;
  link.channels = {"R", "G", "B"};
  link.channels.insert(link.channels.end(), extra.begin(), extra.end());
  int wake[2];
  if (::pipe2(wake, O_CLOEXEC | O_NONBLOCK) != 0) {
    link.drop("cannot make its pipe: " + system_error_text(errno));
    return;
  }
  link.wake_read = wake[0], link.wake_write = wake[1];
  try {
    link.thread = std::thread(serve, link_);
  } catch (const std::system_error& e) {  // no thread to be had (ulimit -u)
    link.drop(std::string("cannot start its thread: ") + e.what());
  }
}

TevDisplay::~TevDisplay() {
  Link& link = *link_;
  bool leave_behind = false;
  {
    const std::lock_guard lock(link.mutex);
    link.closing = true;
    link.silent = true;
    leave_behind = link.resolving;
    link.changed.notify_all();
  }
  if (link.wake_write >= 0) (void)!::write(link.wake_write, "x", 1);
  if (!link.thread.joinable()) return;
  // A resolver that does not answer is not waited for: the thread holds its own share of the
  // link, and ends with the process if not before.
  if (leave_behind) {
    link.thread.detach();
  } else {
    link.thread.join();
  }
}

void TevDisplay::show(const Film& film, const std::vector<ExtraChannel>& extra) {
  Link& link = *link_;
  if (film.width() < 1 || extra.size() + 3 != link.channels.size()) return;
  {
    const std::lock_guard lock(link.mutex);
    if (link.ended) return;
  }
  // The channels created, every time: an update of fewer would leave tev's others stale.
  Link::Picture picture;
  picture.width = film.width(), picture.height = film.height();
  const std::size_t count = link.channels.size(), pixels = film.pixels().size();
  picture.values.resize(pixels * count);
  for (std::size_t p = 0; p < pixels; ++p) {
    float* out = &picture.values[p * count];
    const Color& c = film.pixels()[p];
    out[0] = c.x, out[1] = c.y, out[2] = c.z;
    for (std::size_t e = 0; e < extra.size(); ++e) out[3 + e] = extra[e].values[p];
  }
  const std::lock_guard lock(link.mutex);
  link.pending = std::move(picture);  // a picture not yet sent is replaced: only the latest counts
  link.changed.notify_all();
}

void TevDisplay::finish(const std::atomic<bool>& stop) {
  Link& link = *link_;
  const Clock::time_point deadline = Clock::now() + kViewerTime;
  std::unique_lock lock(link.mutex);
  while (!link.ended && (link.pending || link.sending)) {
    if (stop.load()) return;  // the user's signal: the viewer is not waited for
    if (Clock::now() >= deadline) {
      const std::string seconds = std::to_string(kViewerSeconds) + " s";
      if (link.resolving) {
        link.warn("finding it took more than " + seconds + " (its resolver did not answer)",
                  "nothing was shown");
      } else {
        link.warn("the viewer did not take the last picture within " + seconds,
                  "it may show less than the file");
      }
      return;
    }
    link.changed.wait_for(lock, std::chrono::milliseconds(20));
  }
}

}  // namespace rtiow
