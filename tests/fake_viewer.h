#pragma once
// The viewer's end of --display: a tev that accepts one connection on 127.0.0.1 and keeps every
// byte it is sent until the sender closes (or a minute passes), or one that is slow at it: never
// reading, or reading a little at a time, as a stalled or crawling viewer does.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>

namespace rtiow::test {

// A TCP socket bound to a free port of 127.0.0.1, listening when `listen` is asked; 0 for the
// port when that fails. `receive_buffer` (bytes) bounds what the kernel takes for the reader.
inline int bound_loopback_socket(bool listen, int& port, int receive_buffer = 0) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (receive_buffer > 0) {
    ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &receive_buffer, sizeof receive_buffer);
  }
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof address;
  const bool bound = ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0 &&
                     (!listen || ::listen(fd, 1) == 0) &&
                     ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) == 0;
  port = bound ? ntohs(address.sin_port) : 0;
  return fd;
}

// How the fake viewer reads what it is sent.
enum class ViewerPace {
  Everything,  // at once, as tev does
  Never,       // accepts, then reads nothing
  Crawling,    // 4 KB every half second
};

class FakeTev {
 public:
  explicit FakeTev(ViewerPace pace = ViewerPace::Everything) {
    const bool slow = pace != ViewerPace::Everything;
    listening_ = bound_loopback_socket(/*listen=*/true, port_, slow ? 4096 : 0);
    if (port_ == 0) return;
    reader_ = std::thread([this, pace] {
      pollfd ready{listening_, POLLIN, 0};
      if (::poll(&ready, 1, 60000) <= 0) return;
      const int connection = ::accept(listening_, nullptr, nullptr);
      if (connection < 0) return;
      const auto until = std::chrono::steady_clock::now() + std::chrono::minutes(1);
      char buffer[1 << 16];
      while (!done_ && std::chrono::steady_clock::now() < until) {
        if (pace == ViewerPace::Never) {
          std::this_thread::sleep_for(std::chrono::milliseconds(10));
          continue;
        }
        const std::size_t take = pace == ViewerPace::Crawling ? 4096 : sizeof buffer;
        const ssize_t n = ::recv(connection, buffer, take, 0);
        if (n <= 0) break;
        bytes_.append(buffer, std::size_t(n));
        if (pace == ViewerPace::Crawling)
          std::this_thread::sleep_for(std::chrono::milliseconds(500));
      }
      ::close(connection);
    });
  }
  ~FakeTev() {
    done_ = true;
    if (reader_.joinable()) reader_.join();
    ::close(listening_);
  }
  FakeTev(const FakeTev&) = delete;
  FakeTev& operator=(const FakeTev&) = delete;
  int port() const { return port_; }
  // Everything received, once the sender has closed.
  const std::string& received() {
    if (reader_.joinable()) reader_.join();
    return bytes_;
  }

 private:
  int listening_ = -1;
  int port_ = 0;
  std::thread reader_;
  std::atomic<bool> done_{false};
  std::string bytes_;
};

}  // namespace rtiow::test
