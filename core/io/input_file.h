#pragma once
// Files rtiow reads (scene files, checkpoints, part files, images to compare) are input like
// any other. Each is opened once, without blocking (a FIFO cannot hang the open), and checked
// on the descriptor itself (so what is checked is what is read, whatever happens to its name
// meanwhile): a regular file, no larger than a stated limit. A directory, a FIFO, a device or a
// huge file is refused with one line instead of a read without bound. State that rtiow
// continues (a checkpoint, a cached reference) must be rtiow's own besides: no link, no hard
// link, and this user's, so no one else's file is ever continued. Files are told apart by
// identity, not by spelling.

#include <cstdint>
#include <optional>
#include <string>

namespace rtiow {

// What a file is to rtiow: data it reads (a scene, an image, a part: anyone's, through a link
// if the user gave one), or state it continues, which must be its own file.
enum class InputKind { Data, OwnState };

class InputFile {
 public:
  // Opens `path` for reading; throws InvalidInput "<what> 'path': <reason>" unless it is a
  // readable regular file of at most `max_bytes` (and, for OwnState, no symbolic link, one
  // name only, and this user's). A process out of descriptors or memory is not the file's
  // fault: that throws std::runtime_error saying so.
  InputFile(const std::string& path, std::uint64_t max_bytes, const char* what,
            InputKind kind = InputKind::Data);
  // The same, or nothing when no file has that name.
  static std::optional<InputFile> open_if_present(const std::string& path, std::uint64_t max_bytes,
                                                  const char* what,
                                                  InputKind kind = InputKind::Data);
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
  // Up to `size` bytes from the file's start (fewer when it is shorter): what its first bytes
  // say it is (core/io/image_signature.h).
  std::string first_bytes(std::size_t size) const;
  // Gives up the descriptor (to fdopen, say): the caller closes it.
  int release();

 private:
  InputFile() = default;
  void open(const std::string& path, std::uint64_t max_bytes, const char* what, InputKind kind,
            bool missing_ok);

  int fd_ = -1;
  std::uint64_t size_ = 0;
  std::string path_;
};

// True if both paths exist and name the same file (same device and inode), however spelt.
bool same_file(const std::string& a, const std::string& b);

}  // namespace rtiow
