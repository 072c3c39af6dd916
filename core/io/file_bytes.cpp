#include "core/io/file_bytes.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace rtiow {

bool write_file_bytes(const std::string& path, const std::vector<unsigned char>& bytes,
                      std::string& reason) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    reason = std::strerror(errno);
    return false;
  }
  errno = 0;
  const unsigned char* data = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    data += n;
    left -= std::size_t(n);
  }
  const bool written = left == 0 && ::fsync(fd) == 0;
  if (!written) reason = errno == 0 ? "the write stopped short" : std::strerror(errno);
  if (::close(fd) != 0 && written) {
    reason = std::strerror(errno);
    return false;
  }
  return written;
}

}  // namespace rtiow
