#pragma once
// Writing an encoded file's bytes to disk so that every failure is seen: a short write, a
// full disk, a file-size limit, a failed flush. Image encoders work in memory and hand their
// bytes here, so no codec ever touches the disk (and none can end the process on a failed
// write, as libjpeg's default error handler does).

#include <string>
#include <vector>

namespace rtiow {

// Writes `bytes` to a new file at `path` and flushes it to the disk; false with the
// system's reason on failure (the file may then be partial: callers write a temporary).
bool write_file_bytes(const std::string& path, const std::vector<unsigned char>& bytes,
                      std::string& reason);

}  // namespace rtiow
