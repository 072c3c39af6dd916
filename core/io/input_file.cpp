#include "core/io/input_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/limits/error.h"

namespace rtiow {

std::uint64_t check_input_file(const std::string& path, std::uint64_t max_bytes, const char* what) {
  const std::string name = std::string(what) + " " + quote_value(path);
  if (path.empty()) throw InvalidInput(std::string(what) + ": the path is empty");
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    throw InvalidInput(name + ": " + std::strerror(errno));
  }
  if (S_ISDIR(info.st_mode)) throw InvalidInput(name + ": is a directory, not a file");
  if (!S_ISREG(info.st_mode)) {
    throw InvalidInput(name + ": is not a regular file (a device, FIFO or socket)");
  }
  if (std::uint64_t(info.st_size) > max_bytes) {
    throw InvalidInput(name + ": is " + std::to_string(std::uint64_t(info.st_size) >> 20) +
                       " MiB, more than the limit of " + std::to_string(max_bytes >> 20) + " MiB");
  }
  if (::access(path.c_str(), R_OK) != 0) throw InvalidInput(name + ": " + std::strerror(errno));
  return std::uint64_t(info.st_size);
}

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {
  }, sb{};
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

}  // namespace rtiow
