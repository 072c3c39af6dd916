#include "app/render/output_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/limits/error.h"

namespace rtiow {

namespace {

std::string read_pid(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string pid(text, n > 0 ? std::size_t(n) : 0);
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  for (const char c : pid) {
    if (c < '0' || c > '9') return "unknown";
  }
  return pid.empty() ? "unknown" : pid;
}

// Whether `fd` is what the name `name` in `dir_fd` still is: a lock whose holder removed it
// between our open and our lock is not the lock any more.
bool still_named(int dir_fd, const std::string& name, int fd) {
  struct stat held {
  }, named{};
  return ::fstat(fd, &held) == 0 &&
         ::fstatat(dir_fd, name.c_str(), &named, AT_SYMLINK_NOFOLLOW) == 0 &&
         held.st_ino == named.st_ino && held.st_dev == named.st_dev;
}

}  // namespace

namespace {

std::string lock_name(const std::filesystem::path& output) {
  std::string name = ".";  // appended, not `"." + ...`: GCC 12 warns falsely (-Wrestrict)
  name.append(output.filename().string()).append(".rtiow-lock");
  return name;
}

}  // namespace

OutputLock::OutputLock(const std::string& output) : name_(lock_name(output)) {
  const std::filesystem::path p(output);
  const std::string shown = quote_value((p.parent_path() / name_).string());
  const auto refuse = [&](const std::string& why) {
    throw InvalidInput("output " + quote_value(output) + ": cannot take its lock " + shown + ": " +
                       why);
  };
  const std::string dir = p.parent_path().empty() ? "." : p.parent_path().string();
  dir_fd_ = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd_ < 0) refuse(std::strerror(errno));

  // A few tries: a stale lock may be removed, or a fresh one made, between our steps.
  for (int attempt = 0; attempt < 5; ++attempt) {
    bool created = true;
    int fd =
        ::openat(dir_fd_, name_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0 && errno == EEXIST) {
      // Someone's lock, live or stale; opened without following a link or blocking on a FIFO,
      // and used only if it is a plain file of this user's.
      created = false;
      fd =
          ::openat(dir_fd_, name_.c_str(), O_RDWR | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
      if (fd < 0 && errno == ENOENT) continue;  // removed meanwhile: create it
      if (fd < 0 && errno == ELOOP)
        refuse("it is a symbolic link, which rtiow never makes; remove it");
      if (fd < 0 && errno == EISDIR)
        refuse("it is a directory, which rtiow never makes; remove it");
      if (fd < 0) refuse(std::strerror(errno));
      struct stat info {};
      const bool fstat_ok = ::fstat(fd, &info) == 0;
      const std::string why = !fstat_ok                    ? std::strerror(errno)
                              : !S_ISREG(info.st_mode)     ? "it is not a regular file (a FIFO, "
                                                             "socket or device); remove it"
                              : info.st_uid != ::geteuid() ? "it belongs to another user; remove it"
                              : info.st_nlink != 1 ? "it has other names (hard links); remove it"
                                                   : "";
      if (!why.empty()) {
        ::close(fd);
        refuse(why);
      }
    }
    if (fd < 0) refuse(std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      const std::string pid = read_pid(fd);
      ::close(fd);
      if (error != EWOULDBLOCK) refuse(std::strerror(error));
      throw InvalidInput("output " + quote_value(output) + ": another rtiow (pid " + pid +
                         ") is rendering to it; wait for it to end, or choose another -o");
    }
    if (!still_named(dir_fd_, name_, fd)) {
      ::close(fd);  // locked a file its holder had just removed: take the new one
      continue;
    }
    fd_ = fd;
    removed_on_abort_ = std::make_unique<RemovedOnAbort>(dir_fd_, name_);
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (created || ::ftruncate(fd_, 0) == 0) {
      [[maybe_unused]] const ssize_t ignored = ::pwrite(fd_, pid.data(), pid.size(), 0);
    }
    return;
  }
  refuse("it kept changing while rtiow tried to take it");
}

OutputLock::~OutputLock() {
  if (fd_ >= 0) {
    // Removed before the release, so a waiting render makes a fresh one; only if the name
    // is still ours.
    if (still_named(dir_fd_, name_, fd_)) ::unlinkat(dir_fd_, name_.c_str(), 0);
    removed_on_abort_.reset();
    ::close(fd_);
  }
  if (dir_fd_ >= 0) ::close(dir_fd_);
}

}  // namespace rtiow
