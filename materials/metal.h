#pragma once
// Metal: mirror reflection perturbed by a point in a ball of radius `fuzz` (clamped to 1).
// Rays perturbed below the surface are absorbed, so fuzzy metal loses energy by design.

#include <algorithm>

#include "core/geometry/surface_hit.h"
#include "core/sampling/sampler.h"
#include "core/sampling/sampling.h"

namespace rtiow {

struct Metal {
  Color albedo;
  float fuzz = 0.0f;
};

inline Metal make_metal(Color albedo, float fuzz) {
  return Metal{albedo, std::min(fuzz, 1.0f)};
}

inline bool scatter(const Metal& m, const Vec3& in_direction, const SurfaceHit& hit,
                    SampleStream& rng, Color& attenuation, Vec3& out_direction) {
  const Vec3 reflected = reflect(normalize(in_direction), hit.normal);
  if (m.fuzz > 0.0f) {
    const float u1 = rng.next_1d(), u2 = rng.next_1d(), u3 = rng.next_1d();
    out_direction = reflected + m.fuzz * sample_in_unit_sphere(u1, u2, u3);
  } else {
    out_direction = reflected;
  }
  attenuation = m.albedo;
  return dot(out_direction, hit.normal) > 0.0f;
}

}  // namespace rtiow
