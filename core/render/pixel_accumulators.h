#pragma once
// The per-pixel state of a render in progress (row major, film-sized): what the sample loop
// adds to, and what a checkpoint keeps.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/film/first_hit_sum.h"
#include "core/film/pixel_variance.h"
#include "core/film/sample_sum.h"

namespace rtiow {

struct PixelAccumulators {
  std::vector<PixelSum> sums;
  std::vector<PixelSpread> spreads;
  std::vector<std::uint32_t> samples;   // how many each pixel has, from the first sample
  std::vector<std::uint64_t> rays;      // how many rays they traced (adaptive sampling's cost)
  std::vector<FirstHitSum> first_hits;  // the passes' sums: empty unless passes are asked

  explicit PixelAccumulators(std::size_t pixels, bool keep_first_hits = false)
      : sums(pixels),
        spreads(pixels),
        samples(pixels, 0),
        rays(pixels, 0),
        first_hits(keep_first_hits ? pixels : 0) {}
};

}  // namespace rtiow
