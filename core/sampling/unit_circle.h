#pragma once
// The point of the unit circle at a fraction of a turn, for the warps of sampling.h: a
// direction's azimuth, a lens sample's angle. A dozen multiplies inline where sincosf was a
// library call on the per-bounce path (4-5% of a render), accurate to a few float ulps
// (tested against double over two whole turns).

#include <cmath>
#include <numbers>

namespace rtiow {

struct CirclePoint {
  float cos;
  float sin;
};

// cos and sin of 2 pi * turns, for |turns| <= 2^20 (the warps pass [-1, 1]).
inline CirclePoint circle_point(float turns) {
  // The nearest quarter turn, then a remainder in [-pi/4, pi/4] where the Taylor
  // polynomials below are exact to float precision (their first omitted terms are below
  // 3e-8 there). `quarters - nearest` is exact.
  const float quarters = 4.0f * turns;
  const float nearest = std::floor(quarters + 0.5f);
  const float x = (quarters - nearest) * (std::numbers::pi_v<float> / 2.0f);
  const float x2 = x * x;
  const float s =
      x * (1.0f + x2 * (-1.0f / 6.0f +
                        x2 * (1.0f / 120.0f + x2 * (-1.0f / 5040.0f + x2 * (1.0f / 362880.0f)))));
  const float c =
      1.0f + x2 * (-0.5f + x2 * (1.0f / 24.0f + x2 * (-1.0f / 720.0f + x2 * (1.0f / 40320.0f))));
  // Turn (c, s) by the quarter turns: 1 gives (-s, c), 2 (-c, -s), 3 (s, -c). The count mod 4
  // stays a float (exact here), so a NaN turns into a NaN point rather than an undefined
  // float-to-int conversion.
  const float quadrant = nearest - 4.0f * std::floor(0.25f * nearest);
  const bool odd = quadrant == 1.0f || quadrant == 3.0f;
  const float a = odd ? s : c;
  const float b = odd ? c : s;
  return {(quadrant == 1.0f || quadrant == 2.0f) ? -a : a, quadrant >= 2.0f ? -b : b};
}

}  // namespace rtiow
