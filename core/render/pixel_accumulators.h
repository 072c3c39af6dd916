#pragma once
// The per-pixel state of a render in progress (row major, film-sized): what the sample loop
// adds to, and what a checkpoint keeps.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/film/pixel_sums.h"

namespace rtiow {

struct PixelAccumulators {
  PixelSums sums;                      // the exact sums: colour, spread, and first hits if asked
  std::vector<std::uint32_t> samples;  // how many each pixel has, from the first sample
  std::vector<std::uint64_t> rays;     // how many rays they traced (adaptive sampling's cost)

  explicit PixelAccumulators(std::size_t pixels, bool keep_first_hits = false)
      : sums(pixels, /*keep_spreads=*/true, keep_first_hits), samples(pixels, 0), rays(pixels, 0) {}
};

}  // namespace rtiow
