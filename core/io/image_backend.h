#pragma once
// Finding the image backend (core/io/image_file.h) at run time. The backend is a shared
// library, librtiow_image_io.so, that rtiow does not link: it is looked up
//   1. among the libraries already loaded (a program that linked it, as users of an
//      installed rtiow do by linking rtiow::image_io),
//   2. in the lib directory beside the program's bin directory (the build tree and the
//      installed layout alike),
//   3. by name, through the program's run path and the system's library path.
// `rtiow --version`, `rtiow scene` and every refused input then start in milliseconds, and
// a render can load the backend on a second thread while it renders (preload_image_backend).

#include <cstdint>
#include <memory>
#include <string>

#include "core/io/input_file.h"

namespace rtiow {

class ImageBackend;
class ImageReader;

// Changes whenever image_file.h changes shape: a backend from another build is refused.
inline constexpr int kImageBackendAbi = 5;

// The name the backend's file has.
inline constexpr const char* kImageBackendFile = "librtiow_image_io.so";

// Starts loading the backend on a background thread, where the file is found beside the
// program; otherwise loads it now. Throws std::runtime_error as image_backend() does when
// it is missing, so a command can refuse before its work rather than lose it.
void preload_image_backend();

// An image file rtiow reads (a part file, an image to compare, a cached reference), opened:
// checked first like any input (core/io/input_file.h, at most `max_bytes`, of `kind`), its
// format recognised from its first bytes (core/io/image_signature.h) before any image reader
// sees it, then its header read and its declared size checked against rtiow's image limits
// and against what the file's size can hold in its format (core/io/image_expansion.h; a
// PNM header is read by rtiow itself first), before any pixel
// is allocated. Throws InvalidInput "<name>: <reason>" in one line.
std::unique_ptr<ImageReader> open_input_image(const std::string& path, const std::string& name,
                                              std::uint64_t max_bytes, const char* what,
                                              InputKind kind = InputKind::Data);

// The backend, loaded now unless a preload did it (waits for one under way). Throws
// std::runtime_error naming the places it looked when there is none.
const ImageBackend& image_backend();

}  // namespace rtiow
