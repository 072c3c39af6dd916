#pragma once
// Files rtiow reads (scene files, part files) are input like any other: before a byte is
// read, the path must name a regular file (after links) no larger than a stated limit, so
// a directory, a FIFO, /dev/zero or a huge file is refused with one line instead of a
// read without bound. Files are told apart by identity, not by spelling.

#include <cstdint>
#include <string>

namespace rtiow {

// Throws InvalidInput "<what> 'path': <reason>" unless `path` is a readable regular file of
// at most `max_bytes`. Returns its size.
std::uint64_t check_input_file(const std::string& path, std::uint64_t max_bytes, const char* what);

// True if both paths exist and name the same file (same device and inode), however spelt.
bool same_file(const std::string& a, const std::string& b);

}  // namespace rtiow
