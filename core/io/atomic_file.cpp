#include "core/io/atomic_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <stdexcept>

#include "core/io/file_bytes.h"
#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/io/removed_on_abort.h"
#include "core/limits/error.h"

namespace rtiow {
namespace {

constexpr std::size_t kRandomLetters = 8;
constexpr char kAlphabet[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";

// The mode new files get, as open(2) would give 0666: read once, before any thread runs
// (umask can only be read by setting it).
const mode_t kFileMode = [] {
  const mode_t mask = ::umask(022);
  ::umask(mask);
  return mode_t(0666 & ~mask);
}();

// A descriptor closed when it goes out of scope.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }
  // Closes now; false (errno set) if close reports an error (a delayed write failure).
  bool close() {
    const int fd = fd_;
    fd_ = -1;
    return ::close(fd) == 0;
  }

 private:
  int fd_;
};

}  // namespace

std::string unpredictable_letters(std::size_t count) {
  std::string bytes(count, '\0');
  std::size_t got = 0;
  while (got < count) {
    const ssize_t n = ::getrandom(bytes.data() + got, count - got, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error("no random bytes for a file name");
    got += std::size_t(n);
  }
  for (char& c : bytes) c = kAlphabet[static_cast<unsigned char>(c) % (sizeof kAlphabet - 1)];
  return bytes;
}

void write_atomically(const std::string& path,
                      const std::function<bool(int fd, std::string& reason)>& write) {
  // Through the claim of the target: the command's own, held since before its work, or one
  // taken for this write alone.
  std::optional<OutputClaim> for_this_write;
  const OutputClaim* claim = OutputClaim::find(path);
  if (!claim) claim = &for_this_write.emplace(path);
  const int dir = claim->directory();
  const std::string& target_name = claim->name();
  const auto fail = [&](const std::string& why) {
    throw std::runtime_error("cannot write '" + path + "': " + why);
  };

  // Exclusive creation under a fresh random name; a name taken (by chance, or by someone who
  // guessed it) is simply not used.
  std::string name;
  int fd = -1;
  for (int attempt = 0; fd < 0 && attempt < 100; ++attempt) {
    name = "." + target_name + kTemporaryMark + unpredictable_letters(kRandomLetters);
    fd = ::openat(dir, name.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (fd < 0 && errno != EEXIST) fail(system_error_text(errno));
  }
  if (fd < 0) fail("no free temporary name in its directory");
  Descriptor file(fd);
  const RemovedOnAbort registered(dir, name);

  std::string reason;
  bool written = false;
  try {
    written = write(file.get(), reason);
  } catch (const std::exception& e) {
    reason = e.what();
  }
  const auto discard = [&](const std::string& why) {
    ::unlinkat(dir, name.c_str(), 0);
    fail(why);
  };
  if (!written) discard(reason.empty() ? "the write failed" : reason);
  // Durable before it replaces anything: a power cut leaves the old file or the new one.
  if (::fchmod(file.get(), kFileMode) != 0 || ::fsync(file.get()) != 0 || !file.close()) {
    discard(system_error_text(errno));
  }
  if (::renameat(dir, name.c_str(), dir, target_name.c_str()) != 0) {
    discard(system_error_text(errno));
  }
  ::fsync(dir);  // the rename itself, on the disk
}

void write_bytes_atomically(const std::string& path, const std::vector<unsigned char>& bytes) {
  write_atomically(path, [&](int fd, std::string& reason) {
    return write_all(fd, bytes.data(), bytes.size(), reason);
  });
}

void write_text_atomically(const std::string& path, const std::string& text) {
  write_atomically(path, [&](int fd, std::string& reason) {
    return write_all(fd, text.data(), text.size(), reason);
  });
}

bool is_temporary_of(const std::string& target_name, const std::string& name) {
  const std::string prefix = "." + target_name + kTemporaryMark;
  if (name.size() != prefix.size() + kRandomLetters ||
      name.compare(0, prefix.size(), prefix) != 0) {
    return false;
  }
  for (std::size_t i = prefix.size(); i < name.size(); ++i) {
    if (std::strchr(kAlphabet, name[i]) == nullptr || name[i] == '\0') return false;
  }
  return true;
}

int remove_stale_temporaries(int dir_fd, const std::string& target_name) {
  // A descriptor of its own: closedir closes what fdopendir was given.
  const int own = ::openat(dir_fd, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (own < 0) return 0;
  DIR* dir = ::fdopendir(own);
  if (!dir) {
    ::close(own);
    return 0;
  }
  int removed = 0;
  while (const dirent* entry = ::readdir(dir)) {
    const std::string name = entry->d_name;
    if (!is_temporary_of(target_name, name)) continue;
    struct stat info {};
    if (::fstatat(dir_fd, name.c_str(), &info, AT_SYMLINK_NOFOLLOW) != 0) continue;
    if (!S_ISREG(info.st_mode) || info.st_uid != ::geteuid()) continue;
    if (::unlinkat(dir_fd, name.c_str(), 0) == 0) ++removed;
  }
  ::closedir(dir);
  return removed;
}

}  // namespace rtiow
