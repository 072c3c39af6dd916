#pragma once
// What a material needs to know about the point a ray hit.

#include <cstdint>

#include "core/geometry/vec3.h"

namespace rtiow {

struct SurfaceHit {
  Vec3 point;        // on the surface (re-projected onto the sphere)
  Vec3 normal;       // unit, facing against the incoming ray
  Vec3 point_error;  // per-component bound on the error of `point`
  bool front_face;   // true when the ray arrived from outside
  std::uint32_t material;
};

}  // namespace rtiow
