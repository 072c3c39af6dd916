#pragma once
// Whether an image is one rtiow can hold: the check a render, a part file and a compared
// image share before anything of their size is allocated.

#include <cstdint>

namespace rtiow {

// Throws InvalidInput naming the size unless each side is 1 to limits::kMaxImageSide, the
// pixels are at most limits::kMaxPixels and `bytes_per_pixel` of each fits in half of this
// machine's memory.
void check_image_size(int width, int height, std::uint64_t bytes_per_pixel);

// The machine's physical memory in bytes: what refusals of too large an input measure against.
std::uint64_t physical_memory_bytes();

}  // namespace rtiow
