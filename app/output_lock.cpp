#include "app/output_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>

#include "core/limits/error.h"

namespace rtiow {

namespace {

std::string lock_path(const std::string& output) {
  const std::filesystem::path p(output);
  std::string name = ".";
  name.append(p.filename().string()).append(".rtiow-lock");
  return (p.parent_path() / name).string();
}

std::string read_pid(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string pid(text, n > 0 ? std::size_t(n) : 0);
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid.empty() ? "unknown" : pid;
}

}  // namespace

OutputLock::OutputLock(const std::string& output) : path_(lock_path(output)) {
  // A few tries: the file may be removed by its holder between our open and our lock.
  for (int attempt = 0; attempt < 5; ++attempt) {
    const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) return;
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const std::string pid = read_pid(fd);
      ::close(fd);
      if (errno != EWOULDBLOCK) return;
      throw InvalidInput("output " + quote_value(output) + ": another rtiow (pid " + pid +
                         ") is rendering to it; wait for it to end, or choose another -o");
    }
    struct stat held {
    }, named{};
    if (::fstat(fd, &held) == 0 && ::stat(path_.c_str(), &named) == 0 &&
        held.st_ino == named.st_ino && held.st_dev == named.st_dev) {
      fd_ = fd;
      const std::string pid = std::to_string(::getpid()) + "\n";
      if (::ftruncate(fd_, 0) == 0) {
        [[maybe_unused]] const ssize_t ignored = ::pwrite(fd_, pid.data(), pid.size(), 0);
      }
      return;
    }
    ::close(fd);  // locked a file its holder had just removed: take the new one
  }
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // before the release, so a waiting render makes a fresh one
  ::close(fd_);
}

}  // namespace rtiow
