#pragma once
// The one ray-sphere test. Embree's intersect callback and the naive loop both call it,
// so both accelerators find the same hits, bit for bit.
//
// Numerically careful form (Ray Tracing Gems ch. 7, pbrt-v4 Sphere::BasicIntersect):
// the discriminant comes from the perpendicular distance of the centre to the ray,
// r^2 - |f - (f.d/a) d|^2, which does not cancel catastrophically for small spheres far
// away, and the two roots come from q = -(b' + sign(b') sqrt(disc)) without subtracting
// nearly equal numbers.
//
// Scene data and rays are float (Embree's precision); the test itself runs in double.
// In float, f = origin - centre is rounded to the spacing of the larger of the two, so a
// ground sphere of radius 10^6 under a camera near its top is hit with an error of
// ~0.06 units, and at 10^7 of ~1 unit: spheres sink into the floor and shadows go black.
// In double the same cases are exact to ~10^-9. The cost is a few percent of a render
// (see the README).

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/geometry/ray.h"

namespace rtiow {

// The test in two halves, so that a packet can stop after the first when no ray's
// discriminant is non-negative. The first: the quadratic's terms for a ray whose 1/|d|^2 is given
// (a ray tested against many spheres divides once).
template <typename T>
struct SphereQuadratic {
  T half_b, c, quarter_disc;  // quarter_disc negative or NaN: the line misses
};

template <typename T>
inline SphereQuadratic<T> sphere_quadratic(const Vec3T<T>& center, T radius, const RayT<T>& ray,
                                           T inv_a) {
  const Vec3T<T> f = ray.origin - center;
  const Vec3T<T>& d = ray.direction;
  const T half_b = dot(f, d);
  const T c = dot(f, f) - radius * radius;
  // r^2 - l^2 directly rather than (r - l)(r + l): l^2 is what carries the error either
  // way, and the square root of l would lengthen the test's longest dependency chain.
  const Vec3T<T> perpendicular = f - (half_b * inv_a) * d;
  const T quarter_disc = dot(d, d) * (radius * radius - dot(perpendicular, perpendicular));
  return {half_b, c, quarter_disc};
}

// The second: the nearest root t with t_min < t < t_max, or +infinity when there is none.
template <typename T>
inline T sphere_quadratic_root(const SphereQuadratic<T>& e, T inv_a, T t_min, T t_max) {
  // A negative discriminant makes the root NaN, and every comparison below false.
  const T root = std::sqrt(e.quarter_disc);
  const T q = e.half_b < T(0) ? root - e.half_b : -(e.half_b + root);
  const T ta = q * inv_a;
  const T tb = e.c / q;
  const T t0 = std::min(ta, tb), t1 = std::max(ta, tb);

  constexpr T kNone = std::numeric_limits<T>::infinity();
  const T far = (t1 > t_min && t1 < t_max) ? t1 : kNone;
  return (t0 > t_min && t0 < t_max) ? t0 : far;
}

// Distance to the nearest root t with t_min < t < t_max, or +infinity when there is none,
// computed in T. Written without branches (selects only).
// Negative radii (the book's hollow spheres) intersect like their absolute value.
template <typename T>
inline T sphere_hit_distance(const Vec3T<T>& center, T radius, const RayT<T>& ray, T t_min,
                             T t_max) {
  const T inv_a = T(1) / dot(ray.direction, ray.direction);  // off the critical path
  return sphere_quadratic_root(sphere_quadratic(center, radius, ray, inv_a), inv_a, t_min, t_max);
}

// A cheap conservative pre-test in float for loops over many spheres: false only where
// sphere_hit_distance certainly finds no hit, because the ray's line passes farther from
// the centre than the radius plus a bound on this float evaluation's error (a few ulps of
// |f|, with margin). No square root, one division, and it vectorises.
inline bool sphere_line_may_hit(const Vec3& center, float radius, const Ray& ray) {
  const Vec3 f = ray.origin - center;
  const Vec3& d = ray.direction;
  const Vec3 perpendicular = f - (dot(f, d) / dot(d, d)) * d;
  const float slack = 32.0f * std::numeric_limits<float>::epsilon() *
                      (std::abs(f.x) + std::abs(f.y) + std::abs(f.z));
  const float reach = std::abs(radius) + slack;
  return !(dot(perpendicular, perpendicular) > reach * reach * 1.0001f);
}

// The line test and a second certain miss, for one sphere at a time (Embree's callback):
// the origin is outside the sphere and the ray moves away from the centre, so both roots
// are negative (their product c/a is positive, their sum -2 f.d/a negative). Decided with
// bounds on the float evaluation's error (a few ulps of the magnitudes, with margin), so
// it is false only where sphere_hit_distance finds no hit with t > t_min >= 0.
inline bool sphere_may_hit(const Vec3& center, float radius, const Ray& ray, float t_min) {
  if (!sphere_line_may_hit(center, radius, ray)) return false;
  constexpr float kEps = std::numeric_limits<float>::epsilon();
  const Vec3 f = ray.origin - center;
  const Vec3& d = ray.direction;
  const float ff = dot(f, f), rr = radius * radius;
  const float half_b_error =
      16.0f * kEps * (std::abs(f.x * d.x) + std::abs(f.y * d.y) + std::abs(f.z * d.z));
  const bool leaves_from_outside =
      t_min >= 0.0f && ff - rr > 16.0f * kEps * (ff + rr) && dot(f, d) > half_b_error;
  return !leaves_from_outside;
}

// The nearest float to a double root, kept strictly inside (t_min, t_max). A select, not a
// branch, so the lanes of sphere_hit_distances_exact vectorise.
inline float rounded_inside(double t, float t_min, float t_max) {
  const float rounded = float(t);
  return rounded > t_min && rounded < t_max ? rounded : std::numeric_limits<float>::infinity();
}

// The renderer's test: float scene and ray, double arithmetic, float distance (the nearest
// float to the double root, kept strictly inside (t_min, t_max)).
inline float sphere_hit_distance_exact(const Vec3& center, float radius, const Ray& ray,
                                       float t_min, float t_max) {
  const double t = sphere_hit_distance(Vec3d(center), double(radius),
                                       Rayd{Vec3d(ray.origin), Vec3d(ray.direction)}, double(t_min),
                                       double(t_max));
  return rounded_inside(t, t_min, t_max);
}

// The same, after the float pre-test has turned away the certain misses (a quarter of the
// spheres Embree hands to its callback on the cover), which changes no answer.
inline float sphere_hit_distance(const Vec3& center, float radius, const Ray& ray, float t_min,
                                 float t_max) {
  if (!sphere_may_hit(center, radius, ray, t_min)) return std::numeric_limits<float>::infinity();
  return sphere_hit_distance_exact(center, radius, ray, t_min, t_max);
}

// kLanes rays as arrays of their components (a packet's layout), with each ray's
// 1/|d|^2 in double, computed once for all the spheres the packet meets (inverse_length_squared).
template <int kLanes>
struct RayLanes {
  const float* origin[3];
  const float* direction[3];
  const float* t_min;
  const float* t_max;
  const double* inv_a;
};

// 1/|d|^2 in double for kLanes directions, as sphere_hit_distance computes it.
template <int kLanes>
inline void inverse_length_squared(const float* dx, const float* dy, const float* dz,
                                   double* inv_a) {
  for (int k = 0; k < kLanes; ++k) {
    const Vec3d d{double(dx[k]), double(dy[k]), double(dz[k])};
    inv_a[k] = 1.0 / dot(d, d);
  }
}

// The exact test for kLanes rays at once: lane k is sphere_hit_distance_exact of ray k, in
// branch-free loops over the lanes that GCC computes side by side in SIMD registers (the same
// IEEE operations, no contraction). No float pre-test (it changes no answer, and lanes pay for
// the whole test anyway); but when no lane that `active` marks has a non-negative
// discriminant, no lane can hit, and the square roots and divisions are left out: false, and
// t_out is not written. Otherwise true, with every lane's distance in t_out.
template <int kLanes>
inline bool sphere_hit_distances_exact(const Vec3& center, float radius,
                                       const RayLanes<kLanes>& rays, const int* active,
                                       float* t_out) {
  const Vec3d c{double(center.x), double(center.y), double(center.z)};
  const double r = double(radius);
  SphereQuadratic<double> e[kLanes];
  int any = 0;
  for (int k = 0; k < kLanes; ++k) {
    const Rayd ray{
        {double(rays.origin[0][k]), double(rays.origin[1][k]), double(rays.origin[2][k])},
        {double(rays.direction[0][k]), double(rays.direction[1][k]), double(rays.direction[2][k])}};
    e[k] = sphere_quadratic(c, r, ray, rays.inv_a[k]);
    any |= int(active[k] != 0) & int(e[k].quarter_disc >= 0.0);
  }
  if (!any) return false;
  for (int k = 0; k < kLanes; ++k) {
    const double t =
        sphere_quadratic_root(e[k], rays.inv_a[k], double(rays.t_min[k]), double(rays.t_max[k]));
    t_out[k] = rounded_inside(t, rays.t_min[k], rays.t_max[k]);
  }
  return true;
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
