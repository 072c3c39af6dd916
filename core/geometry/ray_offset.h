#pragma once
// Where a hit lies and where the next ray starts. Instead of the book's fixed
// t_min = 0.001 (wrong at large and small scales), the hit point is re-projected onto the
// sphere, its floating-point error is bounded, and the spawned ray starts just outside that
// error box on the side it leaves to (Woop/Wächter & Binder, Ray Tracing Gems ch. 6;
// pbrt-v4 OffsetRayOrigin). The offset scales with the hit point, so it holds at any scale.

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/geometry/hit.h"
#include "core/geometry/ray.h"
#include "core/geometry/sphere_set.h"
#include "core/geometry/surface_hit.h"

namespace rtiow {

// gamma(n) bounds the relative error of n chained float operations (Higham).
constexpr float float_error_gamma(int n) {
  constexpr float u = std::numeric_limits<float>::epsilon() * 0.5f;
  return float(n) * u / (1.0f - float(n) * u);
}

// The float next to v toward +infinity (`up`) or -infinity (pbrt-v4 NextFloatUp/Down), by
// arithmetic on the bits: a spawned ray's offset points up or down at random per component,
// and as branches (std::nextafter is also a library call; GCC also turned a select on the
// direction into one) they were mispredicted about half the time. The rare cases (a zero, an
// infinity already at the end it moves to, which stays) may branch.
inline float next_float_toward(float v, bool up) {
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(v);
  const bool negative = (bits >> 31) != 0;
  const std::uint32_t magnitude = bits << 1;
  const bool zero = magnitude == 0;  // +0 or -0: to the smallest subnormal of that side
  const bool at_end = magnitude == 0xff000000u && negative != up;
  // Away from zero (+1) when the direction and the sign agree, toward it (-1) otherwise.
  const std::uint32_t moved = bits + 1u - 2u * std::uint32_t(up == negative);
  if (zero) [[unlikely]]
    return std::bit_cast<float>(up ? 1u : 0x80000001u);
  return std::bit_cast<float>(at_end ? bits : moved);
}

inline float next_float_up(float v) {
  return next_float_toward(v, true);
}

inline SurfaceHit make_surface_hit(const SphereSet& spheres, const Ray& ray, const Hit& hit) {
  const Vec3d center(spheres.center(hit.sphere));
  const double radius = spheres.radius[hit.sphere];
  // In double, then rounded once: the point relative to a far-away centre (a huge ground
  // sphere) keeps its precision. Re-projection removes the error t carries along the ray.
  const Vec3d offset = Vec3d(ray.origin) + double(hit.t) * Vec3d(ray.direction) - center;
  const double dist = length(offset);
  // One division (the sqrt and it are the longest chain of a bounce): the unit outward
  // direction, whose sign follows the radius's (hollow spheres), and the point at |radius|.
  const double inv_dist = dist > 0.0 ? 1.0 / dist : 0.0;
  const Vec3d unit_offset = offset * inv_dist;
  const Vec3d point = dist > 0.0 ? center + std::abs(radius) * unit_offset : center + offset;
  SurfaceHit s;
  s.point = Vec3(point);
  // |stored - exact|: the rounding to float (half an ulp of the point) plus the double
  // computation's own error, a few ulps of double of the centre and radius.
  s.point_error =
      float_error_gamma(1) * abs(s.point) +
      Vec3(1e-14 * (abs(center) + Vec3d(std::abs(radius), std::abs(radius), std::abs(radius))));
  const Vec3 outward(radius < 0.0 ? -unit_offset : unit_offset);
  s.front_face = dot(ray.direction, outward) < 0.0f;
  // A sign, not a branch: which face a ray meets is random at a dielectric.
  s.normal = (s.front_face ? 1.0f : -1.0f) * outward;
  s.material = spheres.material[hit.sphere];
  return s;
}

// True when a ray spawned with `direction` starts outside the sphere's ball and moves away
// from it: the ball lies behind the tangent plane, so the ray cannot hit that sphere again,
// and an accelerator may leave it out (the double test, which finds no hit there either,
// is a third of the callbacks on the cover). Decided as spawn_ray picks the side; `radius`
// is the sphere's, whose sign says whether the normal side is the ball's outside.
inline bool leaves_outward(const SurfaceHit& s, const Vec3& direction, float radius) {
  const bool normal_points_out = s.front_face == (radius > 0.0f);
  return !(dot(direction, s.normal) < 0.0f) == normal_points_out;
}

// A ray leaving the surface in `direction`, with an origin outside the hit point's error box.
inline Ray spawn_ray(const SurfaceHit& s, const Vec3& direction) {
  const float d = dot(abs(s.normal), s.point_error);
  // The side is a select, not a branch: a dielectric picks it at random.
  const Vec3 offset = (dot(direction, s.normal) < 0.0f ? -d : d) * s.normal;
  Vec3 origin = s.point + offset;
  // Round away from the surface so rounding in the addition cannot pull the origin back.
  auto away = [](float p, float o) {
    return o > 0.0f || o < 0.0f ? next_float_toward(p, o > 0.0f) : p;
  };
  origin = {away(origin.x, offset.x), away(origin.y, offset.y), away(origin.z, offset.z)};
  return Ray{origin, direction};
}

}  // namespace rtiow
