#pragma once
// A pixel's spread, for adaptive sampling and the variance channels: the sum of squared
// sample values in double, added in sample order by the one task that renders the pixel,
// so it is as deterministic as the image (it is not exact like PixelSum, so shares of a
// render merged from part files carry no variance), and the exact sum of the samples of the
// second replicate (odd sample indices, core/sampling/sampler.h), whose mean against the
// first replicate's is what makes the variance honest (core/film/replicate_variance.h).

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/film/sample_sum.h"
#include "core/geometry/vec3.h"

namespace rtiow {

struct PixelSpread {
  Vec3d squares{0, 0, 0};
  PixelSum odd;  // the samples of odd index

  void add(const Color& c, std::uint64_t sample_index) {
    const double r = PixelSum::counted_value(c.x), g = PixelSum::counted_value(c.y),
                 b = PixelSum::counted_value(c.z);
    squares += Vec3d{r * r, g * g, b * b};
    if (sample_index & 1u) odd.add(c);
  }
};

// The pixel's sample variance over n, per channel, after `n` samples: the variance of its
// mean for independent samples, an overestimate for the Sobol samplers (whose honest
// estimate scales this, core/film/replicate_variance.h). Infinite below two samples, where
// there is no estimate.
inline Vec3d variance_of_mean(const PixelSum& sum, const PixelSpread& spread, std::uint64_t n) {
  if (n < 2) {
    constexpr double inf = INFINITY;
    return {inf, inf, inf};
  }
  const double count = double(n);
  double v[3];
  for (std::size_t c = 0; c < 3; ++c) {
    const double mean = double(sum.channel(int(c))) / PixelSum::kScale / count;
    const double sample_variance =
        std::max(0.0, (spread.squares[c] - count * mean * mean) / (count - 1));
    v[c] = sample_variance / count;
  }
  return {v[0], v[1], v[2]};
}

// The offset in the denominator of the relative error, pbrt-v4's relMSE uses the same: it
// keeps black pixels from demanding unbounded relative accuracy.
inline constexpr double kRelativeErrorOffset = 0.01;

// The pixel's relative variance per sample: the sample variance over (mean + 0.01)^2,
// averaged over R, G, B. Over n samples the pixel's expected relMSE is this over n, so
// sqrt(this / n) is its relative standard error.
inline double relative_sample_variance(const PixelSum& sum, const PixelSpread& spread,
                                       std::uint64_t n) {
  const Vec3d variance = variance_of_mean(sum, spread, n);
  const Color mean = sum.mean(n);
  double total = 0.0;
  for (std::size_t c = 0; c < 3; ++c) {
    const double denominator = double(mean[c]) + kRelativeErrorOffset;
    total += variance[c] * double(n) / (denominator * denominator);
  }
  return total / 3.0;
}

}  // namespace rtiow
