#pragma once
// The one ray-sphere test. Embree's intersect callback and the naive loop both call it,
// so both accelerators find the same hits, bit for bit.
//
// Numerically careful form (Ray Tracing Gems ch. 7, pbrt-v4 Sphere::BasicIntersect):
// the discriminant comes from the perpendicular distance of the centre to the ray,
// r^2 - |f - (f.d/a) d|^2, which does not cancel catastrophically for small spheres far
// away, and the two roots come from q = -(b' + sign(b') sqrt(disc)) without subtracting
// nearly equal numbers.

#include <cmath>

#include "core/ray.h"

namespace rtiow {

// Nearest root t of the ray against the sphere with t_min < t < t_max. Negative radii
// (the book's hollow spheres) intersect like their absolute value.
template <typename T>
inline bool intersect_sphere(const Vec3T<T>& center, T radius, const RayT<T>& ray, T t_min,
                             T t_max, T& t_hit) {
  const Vec3T<T> f = ray.origin - center;
  const Vec3T<T>& d = ray.direction;
  const T a = dot(d, d);
  const T half_b = dot(f, d);
  const T c = dot(f, f) - radius * radius;

  const Vec3T<T> perpendicular = f - (half_b / a) * d;
  const T r = std::abs(radius);
  const T l = length(perpendicular);
  const T quarter_disc = a * ((r - l) * (r + l));
  if (!(quarter_disc >= T(0))) return false;  // also rejects NaN

  const T root = std::sqrt(quarter_disc);
  const T q = half_b < T(0) ? root - half_b : -(half_b + root);
  T t0 = q / a;
  T t1 = c / q;
  if (t0 > t1) std::swap(t0, t1);

  if (t0 > t_min && t0 < t_max) {
    t_hit = t0;
    return true;
  }
  if (t1 > t_min && t1 < t_max) {
    t_hit = t1;
    return true;
  }
  return false;
}

}  // namespace rtiow
