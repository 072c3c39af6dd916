#pragma once
// How many pixels a file can hold, from its size: an image's header is only a claim. A file is
// allowed the pixel memory its format could decode from the bytes present (the format's best
// compression ratio; the bytes themselves for a raw format), plus a fixed allowance, so no file
// makes rtiow allocate more than that multiple of its size (docs/robustness.md). A 200 KB PNG
// claiming 10000x10000 made `diff` use 1.3 GB before it failed.

#include <cstdint>
#include <string>

namespace rtiow {

// The most bytes of pixels, as the header declares their types, one byte of a file of
// `format` (image_format_of's names) can decode to: deflate's 1032 for PNG, an OpenEXR file's
// by its `compression` attribute ("zip", "piz", "dwaa:45", ...), run lengths' for BMP, TGA and
// Radiance HDR, 8 for PNM (a bitmap's bit a pixel). Measured on constant 4000x4000 images
// (oiiotool): PNG 1022, TIFF zip 947 and LZW 352, JPEG 191, EXR zip 978, piz 404, DWAA 3661,
// RLE 62; each bound is the format's own, above what was measured.
std::uint64_t max_expansion(const std::string& format, const std::string& compression);

// The bytes of a PNM file's header that are read to check it.
inline constexpr std::size_t kPnmHeaderBytes = 4096;

// Why `first` (a PNM file's first kPnmHeaderBytes, of `file_bytes` in all) is not a PNM
// image rtiow reads, or "": its width, height and maximum value (P1-P6, PF) or its PAM header
// (P7) within those bytes, and, for the formats whose pixels are stored as they are, every
// byte of them present. The image library would read the whole file looking for a header that
// is not there (a 'P6' and 200 MB of zeros took 326 MB).
std::string why_not_a_pnm_image(const std::string& first, std::uint64_t file_bytes);

}  // namespace rtiow
