#pragma once
// The sum of a pixel's samples, exact and independent of order: each sample is rounded once
// to a fixed-point number with 2^-32 resolution and added as a 128-bit integer. Integer
// addition is associative, so splitting the samples across passes, processes or machines
// and adding the parts gives the same bits as one sequential render.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/film/film.h"
#include "core/geometry/vec3.h"

namespace rtiow {

__extension__ using int128 = __int128;  // a GCC/Clang extension; -Wpedantic knows it is
__extension__ using uint128 = unsigned __int128;

class PixelSum {
 public:
  static constexpr double kScale = 4294967296.0;  // 2^32
  // A single sample's value is clamped to [0, 2^30]: far beyond any radiance a scene of
  // albedos <= 1 under a finite sky produces, and it keeps 2^31 samples from overflowing.
  static constexpr double kMaxSample = 1073741824.0;

  void add(const Color& c) { add_counted(counted_values(c)); }

  // A sample's value as the sum counts it: NaN and infinities as 0, clamped to kMaxSample.
  static double counted_value(float v) {
    return std::isfinite(v) ? std::clamp(double(v), 0.0, kMaxSample) : 0.0;
  }
  static std::array<double, 3> counted_values(const Color& c) {
    return {counted_value(c.x), counted_value(c.y), counted_value(c.z)};
  }

  // Adds a sample already made counted_values: a pixel's sum and its spread take the same
  // sample, converted once (core/film/pixel_variance.h add_sample).
  void add_counted(const std::array<double, 3>& v) {
    channel_[0] += to_fixed(v[0]);
    channel_[1] += to_fixed(v[1]);
    channel_[2] += to_fixed(v[2]);
  }

  // Added as unsigned words: the same bits for sums that fit, and no undefined behaviour
  // for sums read from a hostile part file that do not.
  PixelSum& operator+=(const PixelSum& other) {
    for (int i = 0; i < 3; ++i)
      channel_[i] = int128(uint128(channel_[i]) + uint128(other.channel_[i]));
    return *this;
  }

  bool operator==(const PixelSum&) const = default;

  // The mean of `samples` samples, rounded once to float.
  Color mean(std::uint64_t samples) const {
    const double n = double(samples) * kScale;
    return {float(double(channel_[0]) / n), float(double(channel_[1]) / n),
            float(double(channel_[2]) / n)};
  }

  int128 channel(int i) const { return channel_[i]; }
  void set_channel(int i, int128 value) { channel_[i] = value; }

 private:
  // Round to nearest (values are >= 0, so + 0.5 and truncation do it without a libm call).
  static int128 to_fixed(double counted) {
    return int128(static_cast<std::int64_t>(counted * kScale + 0.5));
  }

  int128 channel_[3]{};
};

// The film from per-pixel sums (row major, film-sized) of `samples` samples each.
inline void resolve(const std::vector<PixelSum>& sums, std::uint64_t samples, Film& film) {
  for (int y = 0; y < film.height(); ++y) {
    for (int x = 0; x < film.width(); ++x) {
      film.at(x, y) =
          sums[std::size_t(y) * std::size_t(film.width()) + std::size_t(x)].mean(samples);
    }
  }
}

// The film from per-pixel sums with each pixel's own sample count (adaptive sampling).
inline void resolve(const std::vector<PixelSum>& sums, const std::vector<std::uint32_t>& samples,
                    Film& film) {
  for (std::size_t p = 0; p < sums.size(); ++p) {
    film.at(int(p % std::size_t(film.width())), int(p / std::size_t(film.width()))) =
        sums[p].mean(samples[p]);
  }
}

}  // namespace rtiow
