#pragma once
// Writing bytes to an open file so that every failure is seen: a short write, a full disk, a
// file-size limit, an interrupted call. Image encoders and the checkpoint writer work in
// memory and hand their bytes here, so no codec ever touches the disk (and none can end the
// process on a failed write, as libjpeg's default error handler does).

#include <cstddef>
#include <string>

namespace rtiow {

// Writes all `size` bytes at `data` to `fd`; false with the system's reason on failure (the
// file may then be partial: callers write a temporary, core/io/atomic_file.h).
bool write_all(int fd, const void* data, std::size_t size, std::string& reason);

}  // namespace rtiow
