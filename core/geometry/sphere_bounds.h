#pragma once
// The box around a sphere that an accelerator may cull with. Padded by a few ulps: it must
// contain every point the float sphere test (core/geometry/sphere_intersect.h) can report,
// or a BVH could skip a hit the naive loop finds and the two would disagree.

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/geometry/vec3.h"

namespace rtiow {

struct Box {
  Vec3 lower, upper;
};

inline Box padded_sphere_bounds(const Vec3& center, float radius) {
  const float r = std::abs(radius);
  auto pad = [](float lo, float hi, float& out_lo, float& out_hi) {
    const float slack =
        4.0f * std::numeric_limits<float>::epsilon() * std::max(std::abs(lo), std::abs(hi));
    out_lo = lo - slack;
    out_hi = hi + slack;
  };
  Box b;
  pad(center.x - r, center.x + r, b.lower.x, b.upper.x);
  pad(center.y - r, center.y + r, b.lower.y, b.upper.y);
  pad(center.z - r, center.z + r, b.lower.z, b.upper.z);
  return b;
}

}  // namespace rtiow
