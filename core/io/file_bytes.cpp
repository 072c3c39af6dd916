#include "core/io/file_bytes.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace rtiow {

bool write_all(int fd, const void* data, std::size_t size, std::string& reason) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  while (size > 0) {
    errno = 0;
    const ssize_t n = ::write(fd, bytes, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      reason = errno == 0 ? "the write stopped short" : std::strerror(errno);
      return false;
    }
    bytes += n;
    size -= std::size_t(n);
  }
  return true;
}

}  // namespace rtiow
