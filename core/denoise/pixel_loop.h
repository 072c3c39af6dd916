#pragma once
// The denoiser's loops whose every pixel's result is its own (a variance, a blend, a guide's
// plane): in parallel over rows of pixels, the same bits for any thread count.

#include <cstddef>

#include "core/parallel/parallel_for_range.h"

namespace rtiow {

// Rows of pixels one task takes.
inline constexpr std::size_t kPixelRowsPerTask = 16;

// body(p) for every pixel p of a width x height image, row major.
template <typename Body>
void for_each_pixel(int width, int height, const Body& body) {
  const auto row = std::size_t(width);
  parallel_for_range(std::size_t(height), kPixelRowsPerTask, [&](std::size_t y0, std::size_t y1) {
    for (std::size_t p = y0 * row; p < y1 * row; ++p) body(p);
  });
}

}  // namespace rtiow
