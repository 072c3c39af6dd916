#pragma once
// The closed set of materials. A std::variant dispatches with a switch, not a virtual
// call per bounce, and a scene without glass never runs refraction code.

#include <variant>

#include "materials/dielectric.h"
#include "materials/lambertian.h"
#include "materials/metal.h"

namespace rtiow {

using Material = std::variant<Lambertian, Metal, Dielectric>;

// Samples the scattered direction; false when the ray is absorbed.
inline bool scatter(const Material& material, const Vec3& in_direction, const SurfaceHit& hit,
                    SampleStream& rng, Color& attenuation, Vec3& out_direction) {
  return std::visit(
      [&](const auto& m) {
        return scatter(m, in_direction, hit, rng, attenuation, out_direction);
      },
      material);
}

}  // namespace rtiow
