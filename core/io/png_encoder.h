#pragma once
// PNG, rtiow's default output, encoded by rtiow itself through libpng: a render that writes a
// PNG never loads the image library's 260 shared objects (about 0.25 s of CPU, taken from a
// 2-core render while it runs). The file holds what the image library wrote: 8-bit RGB, gamma
// 2.0 (gAMA), the image's attributes as text chunks.

#include <cstdint>
#include <string>
#include <vector>

#include "core/io/image_file.h"

namespace rtiow {

// Encodes `rgb` (header.width x header.height pixels, 3 bytes each, row major) into `bytes`,
// with every string attribute of `header` as a tEXt chunk. False (and `reason`) on failure.
bool encode_png(const ImageHeader& header, const std::uint8_t* rgb,
                std::vector<unsigned char>& bytes, std::string& reason);

}  // namespace rtiow
