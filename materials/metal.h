#pragma once
// Metal: the unit mirror direction moved by `fuzz` (in [0, 1]) times a uniform random unit
// vector, as the book's program does since its 4.0 edition (3.x added a point inside the ball
// of radius `fuzz`, which loses less light below the surface: with it, rtiow's cover was 0.025%
// brighter than the book's program, docs/accuracy.md).
// make_metal clamps a larger fuzz to 1, as the book does (scene files go through it, so a
// fuzz above 1 in a file acts as 1); a Metal built directly with fuzz > 1 is refused.
// Rays perturbed below the surface are absorbed, so fuzzy metal loses energy by design.

#include <algorithm>

#include "core/geometry/surface_hit.h"
#include "core/sampling/sample_layout.h"
#include "core/sampling/sampling.h"
#include "materials/material_parameters.h"
#include "materials/scattered.h"

namespace rtiow {

struct Metal {
  Color albedo;
  float fuzz = 0.0f;

  static constexpr const char* kType = "metal";
  static constexpr const char* kDoc = "mirror reflection, blurred by fuzz";
  static constexpr auto parameters() {
    return std::tuple{
        ColorParameter<Metal>{"albedo", &Metal::albedo, 0.0f, 1.0f,
                              "the fraction of light reflected, per channel (R, G, B)"},
        NumberParameter<Metal>{
            "fuzz", &Metal::fuzz, 0.0f, 0.0f, 1.0f, true,
            "how far a random unit vector moves the unit mirror direction (0: a mirror)"}};
  }
};

inline Metal make_metal(Color albedo, float fuzz) {
  return Metal{albedo, std::min(fuzz, 1.0f)};
}

// The bounce dimensions scatter reads: none for a mirror.
constexpr unsigned bounce_uses(const Metal& m) {
  return m.fuzz > 0.0f ? kUsesDirection : kUsesNothing;
}

inline std::optional<Scattered> scatter(const Metal& m, const Vec3& in_direction,
                                        const SurfaceHit& hit, const BounceSample& u) {
  Vec3 direction = reflect(normalize(in_direction), hit.normal);
  if (m.fuzz > 0.0f) {
    direction = direction + m.fuzz * sample_unit_vector(u.direction[0], u.direction[1]);
  }
  if (!(dot(direction, hit.normal) > 0.0f)) return std::nullopt;  // below the surface
  return Scattered{direction, m.albedo};
}

}  // namespace rtiow
