#include "core/io/output_claim.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/io/checksum.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"

namespace rtiow {
namespace {

namespace fs = std::filesystem;

std::mutex g_claims_mutex;
std::vector<const OutputClaim*> g_claims;

std::string directory_of(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

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
// The lock a cleaner cannot take away: an abstract socket (Linux; no file, released with the
// process) bound to a name of the output's directory (device, inode) and its name. Its fd, or
// -1 with `error` set (EADDRINUSE: another rtiow holds it).
int bind_lock_name(int dir_fd, const std::string& name, int& error) {
  struct stat dir {};
  if (::fstat(dir_fd, &dir) != 0) {
    error = errno;
    return -1;
  }
  Checksum digest;
  digest.update(name.data(), name.size());
  char abstract[96];
  const int length =
      std::snprintf(abstract, sizeof abstract, "%crtiow-output-lock:%llx:%llx:%016llx", '\0',
                    (unsigned long long)dir.st_dev, (unsigned long long)dir.st_ino,
                    (unsigned long long)digest.value());
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::memcpy(address.sun_path, abstract, std::size_t(length));
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    error = errno;
    return -1;
  }
  const auto size = socklen_t(offsetof(sockaddr_un, sun_path) + std::size_t(length));
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&address), size) != 0) {
    error = errno;
    ::close(fd);
    return -1;
  }
  return fd;
}

bool still_named(int dir_fd, const std::string& name, int fd) {
  struct stat held {
  }, named{};
  return ::fstat(fd, &held) == 0 &&
         ::fstatat(dir_fd, name.c_str(), &named, AT_SYMLINK_NOFOLLOW) == 0 &&
         held.st_ino == named.st_ino && held.st_dev == named.st_dev;
}

// Why an existing file at the lock's name is not a lock rtiow may take, or "".
std::string why_not_a_lock(int fd) {
  struct stat info {};
  if (::fstat(fd, &info) != 0) return std::strerror(errno);
  if (!S_ISREG(info.st_mode))
    return "it is not a regular file (a FIFO, socket or device); remove it";
  if (info.st_uid != ::geteuid()) return "it belongs to another user; remove it";
  if (info.st_nlink != 1) return "it has other names (hard links); remove it";
  return {};
}

bool same_directory(int a, int b) {
  struct stat sa {
  }, sb{};
  return ::fstat(a, &sa) == 0 && ::fstat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

std::string lock_name_of(const std::string& name) {
  std::string lock(1, '.');  // not `"." + ...`: GCC 12 warns falsely (-Wrestrict)
  lock.append(name).append(kLockSuffix);
  return lock;
}

// The output's lock file, created, or someone's (live or stale) opened without following a
// link or blocking on a FIFO and kept only if it is a plain file of this user's. `vanished`:
// removed between the two opens (create it then); `refusal`: why the found file is no lock;
// otherwise a negative fd with `error` where neither open could.
struct LockFile {
  int fd = -1;
  bool created = true;
  bool vanished = false;
  std::string refusal;
  int error = 0;
};

LockFile open_lock_file(int dir_fd, const std::string& lock_name) {
  LockFile lock;
  lock.fd =
      ::openat(dir_fd, lock_name.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (lock.fd < 0 && errno == EEXIST) {
    lock.created = false;
    lock.fd = ::openat(dir_fd, lock_name.c_str(),
                       O_RDWR | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (lock.fd < 0 && errno == ENOENT) lock.vanished = true;
    if (lock.fd < 0 && errno == ELOOP)
      lock.refusal = "it is a symbolic link, which rtiow never makes; remove it";
    if (lock.fd < 0 && errno == EISDIR)
      lock.refusal = "it is a directory, which rtiow never makes; remove it";
    if (lock.fd < 0 && errno == ENXIO)
      lock.refusal = "it is a FIFO or socket, which rtiow never makes; remove it";
    if (lock.fd >= 0) {
      lock.refusal = why_not_a_lock(lock.fd);
      if (!lock.refusal.empty()) ::close(lock.fd), lock.fd = -1;
      return lock;
    }
  }
  if (lock.fd < 0) lock.error = errno;
  return lock;
}

}  // namespace

void OutputClaim::refuse_lock(const std::string& why) {
  if (lock_fd_ >= 0) ::close(lock_fd_);
  if (dir_fd_ >= 0) ::close(dir_fd_);
  const std::string shown = quote_value((fs::path(path_).parent_path() / lock_name_).string());
  throw InvalidInput("output " + quote_value(path_) + ": cannot take its lock " + shown + ": " +
                     why);
}

void OutputClaim::open_directory() {
  dir_fd_ = ::open(directory_of(path_).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd_ < 0) {
    const int error = errno;
    if (is_exhausted_resource(error)) {
      throw std::runtime_error("cannot open the directory of output " + quote_value(path_) + ": " +
                               system_error_text(error));
    }
    refuse_lock(std::strerror(error));
  }
  // One command writing one file twice (diff --out-diff x.png --out-z x.png) loses one.
  const std::lock_guard<std::mutex> guard(g_claims_mutex);
  for (const OutputClaim* claim : g_claims) {
    if (claim->name_ == name_ && same_directory(claim->dir_fd_, dir_fd_)) {
      ::close(dir_fd_);
      throw InvalidInput("output " + quote_value(path_) + ": is also " + quote_value(claim->path_) +
                         ", another output of this command");
    }
  }
}

bool OutputClaim::hold_lock(int fd, bool created) {
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    const std::string pid = read_pid(fd);
    ::close(fd);
    if (error != EWOULDBLOCK) refuse_lock(std::strerror(error));
    ::close(dir_fd_);
    throw InvalidInput("output " + quote_value(path_) + ": another rtiow (pid " + pid +
                       ") is writing it; wait for it to end, or choose another name");
  }
  if (!still_named(dir_fd_, lock_name_, fd)) {
    ::close(fd);  // locked a file its holder had just removed: take the new one
    return false;
  }
  // The file's lock holds only while its name does: a cleaner that removes it (as one of
  // /tmp does) would let a second rtiow take a new one. The name's socket holds regardless.
  int error = 0;
  name_lock_fd_ = bind_lock_name(dir_fd_, name_, error);
  if (name_lock_fd_ < 0) {
    ::close(fd);
    ::close(dir_fd_);
    if (error == EADDRINUSE) {
      throw InvalidInput("output " + quote_value(path_) +
                         ": another rtiow is writing it (its lock file was removed); wait for "
                         "it to end, or choose another name");
    }
    throw std::runtime_error("cannot take the lock of output " + quote_value(path_) + ": " +
                             system_error_text(error));
  }
  lock_fd_ = fd;
  removed_on_abort_ = std::make_unique<RemovedOnAbort>(dir_fd_, lock_name_);
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (created || ::ftruncate(lock_fd_, 0) == 0) {
    [[maybe_unused]] const ssize_t ignored = ::pwrite(lock_fd_, pid.data(), pid.size(), 0);
  }
  // The lock is held: no live rtiow writes this output's temporaries.
  removed_ = remove_stale_temporaries(dir_fd_, name_);
  const std::lock_guard<std::mutex> guard(g_claims_mutex);
  g_claims.push_back(this);
  return true;
}

OutputClaim::OutputClaim(const std::string& path)
    : path_(path), name_(fs::path(path).filename().string()), lock_name_(lock_name_of(name_)) {
  open_directory();
  // A few tries: a stale lock may be removed, or a fresh one made, between our steps.
  for (int attempt = 0; attempt < 5; ++attempt) {
    const LockFile lock = open_lock_file(dir_fd_, lock_name_);
    if (lock.vanished) continue;
    if (!lock.refusal.empty()) refuse_lock(lock.refusal);
    if (lock.fd < 0) {
      if (is_exhausted_resource(lock.error)) {
        ::close(dir_fd_);
        throw std::runtime_error("cannot take the lock of output " + quote_value(path) + ": " +
                                 system_error_text(lock.error));
      }
      // The create itself failed: the directory takes no new files (/proc, read-only, not
      // ours), which is what the user must act on, not the lock's name.
      if (lock.created) {
        ::close(dir_fd_);
        throw InvalidInput("output " + quote_value(path) + ": cannot create files in directory " +
                           quote_value(directory_of(path)) + ": " + std::strerror(lock.error));
      }
      refuse_lock(std::strerror(lock.error));
    }
    if (hold_lock(lock.fd, lock.created)) return;
  }
  refuse_lock("it kept changing while rtiow tried to take it");
}

OutputClaim::~OutputClaim() {
  {
    const std::lock_guard<std::mutex> guard(g_claims_mutex);
    g_claims.erase(std::remove(g_claims.begin(), g_claims.end(), this), g_claims.end());
  }
  // Removed before the release, so a waiting command makes a fresh one; only if the name is
  // still ours.
  if (still_named(dir_fd_, lock_name_, lock_fd_)) ::unlinkat(dir_fd_, lock_name_.c_str(), 0);
  removed_on_abort_.reset();
  ::close(name_lock_fd_);
  ::close(lock_fd_);
  ::close(dir_fd_);
}

const OutputClaim* OutputClaim::find(const std::string& path) {
  const std::lock_guard<std::mutex> guard(g_claims_mutex);
  if (g_claims.empty()) return nullptr;
  // The command's own spelling first: its directory may have moved since it was claimed.
  for (const OutputClaim* claim : g_claims) {
    if (claim->path_ == path) return claim;
  }
  const std::string name = fs::path(path).filename().string();
  const int dir = ::open(directory_of(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir < 0) return nullptr;
  const OutputClaim* found = nullptr;
  for (const OutputClaim* claim : g_claims) {
    if (claim->name_ == name && same_directory(claim->dir_fd_, dir)) found = claim;
  }
  ::close(dir);
  return found;
}

}  // namespace rtiow
