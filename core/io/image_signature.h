#pragma once
// What an image file is, from its first bytes: an input is untrusted until they say so. The
// image library would otherwise try every reader it has on a file that is none (a file of
// zeros took 79 s per 500 MB before it said "could not find a format reader"); here the
// refusal costs one read of 32 bytes whatever the file's size, and the one reader named is
// the only one that ever sees the file.

#include <string>

namespace rtiow {

// The bytes image_format_of needs.
inline constexpr std::size_t kImageSignatureBytes = 32;

// The image library's name for the format `first` (the file's first bytes) begins with:
// "png", "openexr", "jpeg", "tiff", "bmp", "pnm" (PPM, PGM, PBM, PFM), "hdr"; TGA, which has
// no signature, only for a name ending in .tga whose header's fields are TGA's: "targa".
// "" when none.
std::string image_format_of(const std::string& first, const std::string& path);

// "PNG, OpenEXR, JPEG, TIFF, BMP, PNM/PFM, Radiance HDR or TGA", for messages.
const char* readable_image_formats();

}  // namespace rtiow
