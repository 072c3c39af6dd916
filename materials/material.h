#pragma once
// The closed set of materials. A std::variant dispatches with a switch, not a virtual
// call per bounce, and a scene without glass never runs refraction code.

#include <variant>

#include "materials/dielectric.h"
#include "materials/lambertian.h"
#include "materials/metal.h"

namespace rtiow {

using Material = std::variant<Lambertian, Metal, Dielectric>;

inline std::optional<ParameterProblem> check_parameters(const Material& material) {
  return std::visit([](const auto& m) { return check_parameters(m); }, material);
}

// The bounce dimensions the material's scatter reads (core/sampling/sample_layout.h).
inline unsigned bounce_uses(const Material& material) {
  switch (material.index()) {
    case 0:
      return bounce_uses(*std::get_if<0>(&material));
    case 1:
      return bounce_uses(*std::get_if<1>(&material));
    default:
      return bounce_uses(*std::get_if<2>(&material));
  }
}

// Samples the scattered ray from the bounce's uniforms; none when the ray is absorbed.
inline std::optional<Scattered> scatter(const Material& material, const Vec3& in_direction,
                                        const SurfaceHit& hit, const BounceSample& u) {
  // A plain switch on the index: GCC 12 leaves std::visit as an out-of-line call here.
  switch (material.index()) {
    case 0:
      return scatter(*std::get_if<0>(&material), in_direction, hit, u);
    case 1:
      return scatter(*std::get_if<1>(&material), in_direction, hit, u);
    default:
      return scatter(*std::get_if<2>(&material), in_direction, hit, u);
  }
}

}  // namespace rtiow
