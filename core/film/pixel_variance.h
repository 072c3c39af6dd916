#pragma once
// A pixel's spread, for adaptive sampling and the variance channels: the exact sum of its
// squared samples and the exact sum of the samples of the second replicate (odd sample
// indices, core/sampling/sampler.h), whose mean against the first replicate's is what makes
// the variance honest (core/film/replicate_variance.h). Both are exact like PixelSum, so the
// shares of a render (passes, threads, part files, MPI ranks) add up to the same variance, bit
// for bit, as one render.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "core/film/sample_sum.h"
#include "core/geometry/vec3.h"

namespace rtiow {

// The sum of a pixel's squared samples, exact and order-free like PixelSum, whose 128-bit
// words it shares (so it merges and is stored the same way): each square, exact in double (a
// float's square), is rounded once to 2^-32. A sample of at most 2^30 squares to at most 2^92
// in fixed point, so 2^31 of them still fit.
class SquareSum : public PixelSum {
 public:
  void add(const Color& c) { add_counted(counted_values(c)); }
  void add_counted(const std::array<double, 3>& v) {
    for (int i = 0; i < 3; ++i) set_channel(i, channel(i) + fixed_square(v[std::size_t(i)]));
  }

  double value(int i) const { return double(channel(i)) / kScale; }

 private:
  static int128 fixed_square(double v) {
    const double scaled = v * v * kScale + 0.5;
    // One conversion instruction below 2^63 (any sample below 46341), a library call above.
    return scaled < 9.2e18 ? int128(static_cast<std::int64_t>(scaled))
                           : static_cast<int128>(scaled);
  }
};

struct PixelSpread {
  SquareSum squares;
  PixelSum odd;  // the samples of odd index

  void add(const Color& c, std::uint64_t sample_index) {
    add_counted(PixelSum::counted_values(c), sample_index);
  }
  void add_counted(const std::array<double, 3>& v, std::uint64_t sample_index) {
    squares.add_counted(v);
    if (sample_index & 1u) odd.add_counted(v);
  }

  PixelSpread& operator+=(const PixelSpread& other) {
    squares += other.squares;
    odd += other.odd;
    return *this;
  }

  bool operator==(const PixelSpread&) const = default;
};

// Adds one sample to a pixel's sum and spread, its value converted to what they count once.
inline void add_sample(PixelSum& sum, PixelSpread& spread, const Color& c,
                       std::uint64_t sample_index) {
  const std::array<double, 3> v = PixelSum::counted_values(c);
  sum.add_counted(v);
  spread.add_counted(v, sample_index);
}

// The sum of squared deviations that rounding alone gives n equal samples: each square and
// each sample are rounded to 2^-32 (by at most 2^-33), and the difference of the sums is taken
// in double. Below three times this the sums cannot tell a pixel's samples apart (floats
// closer than about 2e-5 at 1), and its spread is 0: a constant pixel reports no variance,
// rather than rounding noise that a ratio of neighbours could take for evidence
// (core/film/replicate_variance.cpp).
inline double rounding_of_squared_deviations(double mean, double count) {
  return count * (std::ldexp(1.0 + 2.0 * mean, -33) + mean * mean * std::ldexp(1.0, -50));
}

// The pixel's sample variance over n, per channel, after `n` samples: the variance of its
// mean for independent samples, an overestimate for the Sobol samplers (whose honest
// estimate scales this, core/film/replicate_variance.h). Infinite below two samples, where
// there is no estimate; 0 where the samples are equal to the sums' resolution.
inline Vec3d variance_of_mean(const PixelSum& sum, const PixelSpread& spread, std::uint64_t n) {
  if (n < 2) {
    constexpr double inf = INFINITY;
    return {inf, inf, inf};
  }
  const double count = double(n);
  double v[3];
  for (std::size_t c = 0; c < 3; ++c) {
    const double mean = double(sum.channel(int(c))) / PixelSum::kScale / count;
    const double deviations = spread.squares.value(int(c)) - count * mean * mean;
    const bool resolved = deviations > 3.0 * rounding_of_squared_deviations(mean, count);
    v[c] = resolved ? deviations / (count - 1) / count : 0.0;
  }
  return {v[0], v[1], v[2]};
}

// The offset in the denominator of the relative error, pbrt-v4's relMSE uses the same: it
// keeps black pixels from demanding unbounded relative accuracy.
inline constexpr double kRelativeErrorOffset = 0.01;

// The pixel's relative variance per sample: the sample variance over (mean + 0.01)^2,
// averaged over R, G, B. Over n samples the pixel's expected relMSE is this over n, so
// sqrt(this / n) is its relative standard error.
// `scale` multiplies each channel's variance first (the sampler's gain, replicate_variance.h).
inline double relative_sample_variance(const PixelSum& sum, const PixelSpread& spread,
                                       std::uint64_t n, const Vec3d& scale = {1, 1, 1}) {
  const Vec3d variance = variance_of_mean(sum, spread, n) * scale;
  const Color mean = sum.mean(n);
  double total = 0.0;
  for (std::size_t c = 0; c < 3; ++c) {
    const double denominator = double(mean[c]) + kRelativeErrorOffset;
    total += variance[c] * double(n) / (denominator * denominator);
  }
  return total / 3.0;
}

}  // namespace rtiow
