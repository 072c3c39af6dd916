#include "core/io/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "core/limits/error.h"

namespace rtiow {

InputFile::InputFile(const std::string& path, std::uint64_t max_bytes, const char* what,
                     InputKind kind) {
  open(path, max_bytes, what, kind, false);
}

std::optional<InputFile> InputFile::open_if_present(const std::string& path,
                                                    std::uint64_t max_bytes, const char* what,
                                                    InputKind kind) {
  InputFile file;
  file.open(path, max_bytes, what, kind, true);
  if (file.fd_ < 0) return std::nullopt;
  return std::optional<InputFile>(std::move(file));
}

void InputFile::open(const std::string& path, std::uint64_t max_bytes, const char* what,
                     InputKind kind, bool missing_ok) {
  const bool follow_links = kind == InputKind::Data;
  const std::string name = std::string(what) + " " + quote_value(path);
  if (path.empty()) throw InvalidInput(std::string(what) + ": the path is empty");
  path_ = path;
  // O_NONBLOCK: opening a FIFO must not wait for a writer. It is cleared once the file is
  // known to be a regular file (where it changes nothing anyway).
  const int flags = O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY | (follow_links ? 0 : O_NOFOLLOW);
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) {
    const int error = errno;
    if (error == ENOENT && missing_ok) return;
    if (error == ELOOP && !follow_links) {
      throw InvalidInput(name + ": is a symbolic link, not a file rtiow wrote; remove it");
    }
    if (is_exhausted_resource(error)) {
      throw std::runtime_error("cannot open " + name + ": " + system_error_text(error));
    }
    throw InvalidInput(name + ": " + std::strerror(error));
  }
  fd_ = fd;  // closed by the destructor if a check below throws
  struct stat info {};
  if (::fstat(fd, &info) != 0) throw InvalidInput(name + ": " + std::strerror(errno));
  if (S_ISDIR(info.st_mode)) throw InvalidInput(name + ": is a directory, not a file");
  if (!S_ISREG(info.st_mode)) {
    throw InvalidInput(name + ": is not a regular file (a device, FIFO or socket)");
  }
  if (kind == InputKind::OwnState && info.st_uid != ::geteuid()) {
    throw InvalidInput(name + ": belongs to another user (uid " + std::to_string(info.st_uid) +
                       "); rtiow continues only its own files");
  }
  if (kind == InputKind::OwnState && info.st_nlink != 1) {
    throw InvalidInput(name + ": has other names (hard links), which rtiow never makes; remove it");
  }
  if (std::uint64_t(info.st_size) > max_bytes) {
    throw InvalidInput(name + ": is " + std::to_string(std::uint64_t(info.st_size) >> 20) +
                       " MiB, more than the limit of " + std::to_string(max_bytes >> 20) + " MiB");
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  size_ = std::uint64_t(info.st_size);
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

InputFile::InputFile(InputFile&& other) noexcept
    : fd_(other.fd_), size_(other.size_), path_(std::move(other.path_)) {
  other.fd_ = -1;
}

std::string InputFile::name_for_library() const {
  const std::string by_descriptor = "/proc/self/fd/" + std::to_string(fd_);
  return ::access(by_descriptor.c_str(), R_OK) == 0 ? by_descriptor : path_;
}

std::string InputFile::first_bytes(std::size_t size) const {
  std::string bytes(size, '\0');
  std::size_t got = 0;
  while (got < size) {
    const ssize_t n = ::pread(fd_, bytes.data() + got, size - got, off_t(got));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    got += std::size_t(n);
  }
  bytes.resize(got);
  return bytes;
}

int InputFile::release() {
  const int fd = fd_;
  fd_ = -1;
  return fd;
}

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {
  }, sb{};
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

}  // namespace rtiow
