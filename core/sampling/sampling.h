#pragma once
// Warps from uniform numbers in [0,1) to the distributions the book samples. They are
// closed-form (no rejection loop), so every sample uses a fixed number of dimensions.

#include <cmath>

#include "core/geometry/vec3.h"
#include "core/sampling/unit_circle.h"

namespace rtiow {

// Uniform direction on the unit sphere (Archimedes: z is uniform in [-1, 1]).
inline Vec3 sample_unit_vector(float u1, float u2) {
  const float z = 1.0f - 2.0f * u1;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const CirclePoint azimuth = circle_point(u2);
  return {r * azimuth.cos, r * azimuth.sin, z};
}

// Uniform point inside the unit ball: a uniform direction at radius u^(1/3).
inline Vec3 sample_in_unit_sphere(float u1, float u2, float u3) {
  return std::cbrt(u3) * sample_unit_vector(u1, u2);
}

// Uniform point inside the unit disk (z = 0), Shirley-Chiu concentric mapping: it keeps
// strata compact, which matters once the lens dimensions are stratified.
inline Vec3 sample_in_unit_disk(float u1, float u2) {
  const float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
  if (a == 0.0f && b == 0.0f) return {0.0f, 0.0f, 0.0f};
  // The angle in turns: pi/4 (b/a) or pi/2 - pi/4 (a/b) radians.
  float r, turns;
  if (std::abs(a) > std::abs(b)) {
    r = a;
    turns = 0.125f * (b / a);
  } else {
    r = b;
    turns = 0.25f - 0.125f * (a / b);
  }
  const CirclePoint angle = circle_point(turns);
  return {r * angle.cos, r * angle.sin, 0.0f};
}

}  // namespace rtiow
