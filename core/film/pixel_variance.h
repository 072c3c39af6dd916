#pragma once
// A pixel's spread, for adaptive sampling and the variance channels: the sum of squared
// sample values in double, added in sample order by the one task that renders the pixel,
// so it is as deterministic as the image. (It is not exact like PixelSum, so shares of a
// render merged from part files carry no variance.)

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/film/sample_sum.h"
#include "core/geometry/vec3.h"

namespace rtiow {

struct PixelSquares {
  Vec3d sum{0, 0, 0};

  void add(const Color& c) {
    const double r = PixelSum::counted_value(c.x), g = PixelSum::counted_value(c.y),
                 b = PixelSum::counted_value(c.z);
    sum += Vec3d{r * r, g * g, b * b};
  }
};

// The estimated variance of the pixel's mean (per channel) after `n` samples: the sample
// variance over n. Infinite below two samples, where there is no estimate.
inline Vec3d variance_of_mean(const PixelSum& sum, const PixelSquares& squares, std::uint64_t n) {
  if (n < 2) {
    constexpr double inf = INFINITY;
    return {inf, inf, inf};
  }
  const double count = double(n);
  double v[3];
  for (std::size_t c = 0; c < 3; ++c) {
    const double mean = double(sum.channel(int(c))) / PixelSum::kScale / count;
    const double spread = std::max(0.0, (squares.sum[c] - count * mean * mean) / (count - 1));
    v[c] = spread / count;
  }
  return {v[0], v[1], v[2]};
}

// The offset in the denominator of the relative error, pbrt-v4's relMSE uses the same: it
// keeps black pixels from demanding unbounded relative accuracy.
inline constexpr double kRelativeErrorOffset = 0.01;

// The pixel's relative variance per sample: the sample variance over (mean + 0.01)^2,
// averaged over R, G, B. Over n samples the pixel's expected relMSE is this over n, so
// sqrt(this / n) is its relative standard error.
inline double relative_sample_variance(const PixelSum& sum, const PixelSquares& squares,
                                       std::uint64_t n) {
  const Vec3d variance = variance_of_mean(sum, squares, n);
  const Color mean = sum.mean(n);
  double total = 0.0;
  for (std::size_t c = 0; c < 3; ++c) {
    const double denominator = double(mean[c]) + kRelativeErrorOffset;
    total += variance[c] * double(n) / (denominator * denominator);
  }
  return total / 3.0;
}

}  // namespace rtiow
