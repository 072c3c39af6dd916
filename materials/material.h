#pragma once
// The closed set of materials. A std::variant dispatches with a switch, not a virtual
// call per bounce, and a scene without glass never runs refraction code.
//
// Adding a material: its own file (its struct, its parameters() declaration, bounce_uses and
// scatter) and its name in the list below; the scene format, its checks and its docs follow
// from the declaration (materials/material_parameters.h).

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <variant>

#include "materials/dielectric.h"
#include "materials/lambertian.h"
#include "materials/metal.h"

namespace rtiow {

using Material = std::variant<Lambertian, Metal, Dielectric>;

// f(the material as its own type), by comparing the index in turn (the last is the
// default): GCC 12 leaves std::visit as an out-of-line call on the per-bounce path, and
// inlines this chain as it did a switch.
template <std::size_t I = 0, typename F>
decltype(auto) visit_material(const Material& material, F&& f) {
  if constexpr (I + 1 == std::variant_size_v<Material>) {
    return f(*std::get_if<I>(&material));
  } else {
    if (material.index() == I) return f(*std::get_if<I>(&material));
    return visit_material<I + 1>(material, f);
  }
}

// Calls f(declared type) with a default-made value of each material type, in the list's order.
template <typename F>
void for_each_material_type(F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (f(std::variant_alternative_t<I, Material>{}), ...);
  }
  (std::make_index_sequence<std::variant_size_v<Material>>());
}

// "lambertian, metal or dielectric": the types a scene file may name.
inline std::string material_type_names() {
  std::string names;
  std::size_t i = 0;
  constexpr std::size_t n = std::variant_size_v<Material>;
  for_each_material_type([&](const auto& m) {
    if (i) names += i + 1 == n ? " or " : ", ";
    names += std::decay_t<decltype(m)>::kType;
    ++i;
  });
  return names;
}

inline std::optional<ParameterProblem> check_parameters(const Material& material) {
  return visit_material(material, [](const auto& m) { return check_parameters(m); });
}

// The bounce dimensions the material's scatter reads (core/sampling/sample_layout.h).
inline unsigned bounce_uses(const Material& material) {
  return visit_material(material, [](const auto& m) { return bounce_uses(m); });
}

// The material's colour, for the albedo pass: the albedo it is given, or white for one that
// absorbs nothing (glass).
inline Color albedo(const Material& material) {
  return visit_material(material, [](const auto& m) {
    if constexpr (requires { m.albedo; }) {
      return m.albedo;
    } else {
      return Color{1.0f, 1.0f, 1.0f};
    }
  });
}

// Samples the scattered ray from the bounce's uniforms; none when the ray is absorbed.
inline std::optional<Scattered> scatter(const Material& material, const Vec3& in_direction,
                                        const SurfaceHit& hit, const BounceSample& u) {
  return visit_material(material, [&](const auto& m) { return scatter(m, in_direction, hit, u); });
}

}  // namespace rtiow
