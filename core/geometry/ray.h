#pragma once
// A ray: origin and direction (not necessarily unit length).

#include <cmath>

#include "core/geometry/vec3.h"

namespace rtiow {

template <typename T>
struct RayT {
  Vec3T<T> origin;
  Vec3T<T> direction;

  constexpr Vec3T<T> at(T t) const { return origin + t * direction; }
};

using Ray = RayT<float>;

// Embree asserts on a ray with a NaN or a component beyond 1.844e18 in its origin or
// direction. Camera rays are bounded by validation; this guards every ray a material
// spawns, for both accelerators alike (a path with such a ray ends, black).
inline bool is_traceable(const Ray& r) {
  constexpr float kLimit = 1e18f;
  // Written so that NaN fails every comparison.
  return std::abs(r.origin.x) <= kLimit && std::abs(r.origin.y) <= kLimit &&
         std::abs(r.origin.z) <= kLimit && std::abs(r.direction.x) <= kLimit &&
         std::abs(r.direction.y) <= kLimit && std::abs(r.direction.z) <= kLimit;
}
using Rayd = RayT<double>;

}  // namespace rtiow
