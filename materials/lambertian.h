#pragma once
// Lambertian (ideal diffuse) reflection as in the book: the scattered direction is the
// normal plus a uniform unit vector, which is cosine-distributed about the normal.

#include "core/geometry/surface_hit.h"
#include "core/sampling/sample_layout.h"
#include "core/sampling/sampling.h"
#include "materials/material_parameters.h"
#include "materials/scattered.h"

namespace rtiow {

struct Lambertian {
  Color albedo;

  static constexpr const char* kType = "lambertian";
  static constexpr const char* kDoc = "ideal diffuse reflection, as the book's";
  static constexpr auto parameters() {
    return std::tuple{
        ColorParameter<Lambertian>{"albedo", &Lambertian::albedo, 0.0f, 1.0f,
                                   "the fraction of light reflected, per channel (R, G, B)"}};
  }
};

// The bounce dimensions scatter reads.
constexpr unsigned bounce_uses(const Lambertian&) {
  return kUsesDirection;
}

inline std::optional<Scattered> scatter(const Lambertian& m, const Vec3& /*in_direction*/,
                                        const SurfaceHit& hit, const BounceSample& u) {
  Vec3 direction = hit.normal + sample_unit_vector(u.direction[0], u.direction[1]);
  // The unit vector can cancel the normal; a zero direction would give NaNs downstream.
  if (near_zero(direction)) direction = hit.normal;
  return Scattered{direction, m.albedo};
}

}  // namespace rtiow
