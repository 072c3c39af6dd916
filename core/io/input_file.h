#pragma once
// Files rtiow reads (scene files, checkpoints, part files, images to compare) are input like
// any other. Each is opened once, without blocking (a FIFO cannot hang the open), and checked
// on the descriptor itself (so what is checked is what is read, whatever happens to its name
// meanwhile): a regular file, no larger than a stated limit. A directory, a FIFO, a device or a
// huge file is refused with one line instead of a read without bound. Files are told apart by
// identity, not by spelling.

#include <cstdint>
#include <optional>
#include <string>

namespace rtiow {

class InputFile {
 public:
  // Opens `path` for reading; throws InvalidInput "<what> 'path': <reason>" unless it is a
  // readable regular file of at most `max_bytes`. With `follow_links` false a symbolic link
  // is refused too (for rtiow's own files, which are never links).
  InputFile(const std::string& path, std::uint64_t max_bytes, const char* what,
            bool follow_links = true);
  // The same, or nothing when no file has that name.
  static std::optional<InputFile> open_if_present(const std::string& path, std::uint64_t max_bytes,
                                                  const char* what, bool follow_links = true);
  ~InputFile();
  InputFile(InputFile&& other) noexcept;
  InputFile& operator=(InputFile&&) = delete;
  InputFile(const InputFile&) = delete;

  int fd() const { return fd_; }
  std::uint64_t size() const { return size_; }
  // A name for this very file, for a library that opens files by name: /proc/self/fd/N where
  // /proc is mounted (it reopens the file checked, not whatever the path names now), else the
  // path.
  std::string name_for_library() const;
  // Gives up the descriptor (to fdopen, say): the caller closes it.
  int release();

 private:
  InputFile() = default;
  void open(const std::string& path, std::uint64_t max_bytes, const char* what, bool follow_links,
            bool missing_ok);

  int fd_ = -1;
  std::uint64_t size_ = 0;
  std::string path_;
};

// True if both paths exist and name the same file (same device and inode), however spelt.
bool same_file(const std::string& a, const std::string& b);

}  // namespace rtiow
