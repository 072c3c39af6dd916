#pragma once
// The one ray-sphere test. Embree's intersect callback and the naive loop both call it,
// so both accelerators find the same hits, bit for bit.
//
// Numerically careful form (Ray Tracing Gems ch. 7, pbrt-v4 Sphere::BasicIntersect):
// the discriminant comes from the perpendicular distance of the centre to the ray,
// r^2 - |f - (f.d/a) d|^2, which does not cancel catastrophically for small spheres far
// away, and the two roots come from q = -(b' + sign(b') sqrt(disc)) without subtracting
// nearly equal numbers.

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/ray.h"

namespace rtiow {

// Distance to the nearest root t with t_min < t < t_max, or +infinity when there is none.
// Written without branches (selects only) so that the naive loop vectorises it; the
// vectorised and scalar evaluations perform the same IEEE operations and agree bit for bit.
// Negative radii (the book's hollow spheres) intersect like their absolute value.
template <typename T>
inline T sphere_hit_distance(const Vec3T<T>& center, T radius, const RayT<T>& ray, T t_min,
                             T t_max) {
  const Vec3T<T> f = ray.origin - center;
  const Vec3T<T>& d = ray.direction;
  const T a = dot(d, d);
  const T half_b = dot(f, d);
  const T c = dot(f, f) - radius * radius;

  const Vec3T<T> perpendicular = f - (half_b / a) * d;
  const T r = std::abs(radius);
  const T l = std::sqrt(dot(perpendicular, perpendicular));
  const T quarter_disc = a * ((r - l) * (r + l));

  // A negative discriminant makes the root NaN, and every comparison below false.
  const T root = std::sqrt(quarter_disc);
  const T q = half_b < T(0) ? root - half_b : -(half_b + root);
  const T ta = q / a;
  const T tb = c / q;
  const T t0 = std::min(ta, tb), t1 = std::max(ta, tb);

  constexpr T kNone = std::numeric_limits<T>::infinity();
  const T far = (t1 > t_min && t1 < t_max) ? t1 : kNone;
  return (t0 > t_min && t0 < t_max) ? t0 : far;
}

// A cheap conservative pre-test for loops over many spheres: false only where
// sphere_hit_distance certainly finds no hit, because the ray's line passes farther from the
// centre than the radius by a margin far above rounding error (no square root, one
// division). Callers run the full test where it says true, so results do not change.
template <typename T>
inline bool sphere_may_hit(const Vec3T<T>& center, T radius, const RayT<T>& ray) {
  const Vec3T<T> f = ray.origin - center;
  const Vec3T<T>& d = ray.direction;
  const Vec3T<T> perpendicular = f - (dot(f, d) / dot(d, d)) * d;
  return !(dot(perpendicular, perpendicular) > radius * radius * T(1.0001));
}

// The same test for callers that branch: true and the distance when there is a hit.
template <typename T>
inline bool intersect_sphere(const Vec3T<T>& center, T radius, const RayT<T>& ray, T t_min, T t_max,
                             T& t_hit) {
  const T t = sphere_hit_distance(center, radius, ray, t_min, t_max);
  if (!(t < std::numeric_limits<T>::infinity())) return false;
  t_hit = t;
  return true;
}

}  // namespace rtiow
