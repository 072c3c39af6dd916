#pragma once
// What a sample's camera ray first met, and the exact per-pixel sum of it that the albedo,
// normal and depth passes are the mean of (--passes, core/render/first_hit_passes.h). Exact
// like PixelSum and for the same reason: each value is rounded once to 2^-32 and added as a
// 128-bit integer, so threads, passes, part files, checkpoints and MPI ranks add up to the
// same bits as one render. Unlike radiance a normal is signed, so the words are signed too.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "core/film/sample_sum.h"
#include "core/geometry/vec3.h"

namespace rtiow {

// One sample's first hit; all zero where the camera ray saw the sky (or was not traced).
struct FirstHit {
  Color albedo;        // the material's colour: what it reflects of the light (glass: 1)
  Vec3 normal;         // unit, world space, facing the camera: the normal the material shades with
  float depth = 0.0f;  // the distance from the camera ray's origin (on the lens) to the hit
};

class FirstHitSum {
 public:
  // albedo R, G, B; normal X, Y, Z; depth: the order files store them in.
  static constexpr std::size_t kChannels = 7;
  // A value is clamped to [-2^30, 2^30] (a depth beyond is no distance a scene holds), so
  // 2^31 samples of it still fit in 127 bits.
  static constexpr double kMaxValue = PixelSum::kMaxSample;

  void add(const FirstHit& hit) {
    const std::array<float, kChannels> v{hit.albedo.x, hit.albedo.y, hit.albedo.z, hit.normal.x,
                                         hit.normal.y, hit.normal.z, hit.depth};
    for (std::size_t c = 0; c < kChannels; ++c) channel_[c] += to_fixed(v[c]);
  }

  // Added as unsigned words: no undefined behaviour for sums from a hostile file.
  FirstHitSum& operator+=(const FirstHitSum& other) {
    for (std::size_t c = 0; c < kChannels; ++c)
      channel_[c] = int128(uint128(channel_[c]) + uint128(other.channel_[c]));
    return *this;
  }

  bool operator==(const FirstHitSum&) const = default;

  // The mean of channel c over `samples` samples, rounded once to float (0 without samples).
  float mean(std::size_t c, std::uint64_t samples) const {
    if (samples == 0) return 0.0f;
    return float(double(channel_[c]) / (double(samples) * PixelSum::kScale));
  }

  int128 channel(std::size_t c) const { return channel_[c]; }
  void set_channel(std::size_t c, int128 value) { channel_[c] = value; }

 private:
  // Rounded to nearest, half away from zero; NaN counts as 0.
  static int128 to_fixed(float value) {
    if (!(std::abs(value) <= float(kMaxValue))) {
      value = std::isnan(value) ? 0.0f : std::copysign(float(kMaxValue), value);
    }
    const double scaled = double(value) * PixelSum::kScale;
    return int128(static_cast<std::int64_t>(scaled + (scaled < 0.0 ? -0.5 : 0.5)));
  }

  int128 channel_[kChannels]{};
};

}  // namespace rtiow
