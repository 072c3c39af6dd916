#pragma once
// Dielectric (glass, water, a bubble): reflects with the Fresnel probability (Schlick's, as
// in the book, or exact), refracts otherwise by Snell's law, and reflects totally past the
// critical angle. Nothing is absorbed.

#include <cmath>

#include "core/geometry/surface_hit.h"
#include "core/limits/input_limits.h"
#include "core/sampling/sample_layout.h"
#include "materials/fresnel.h"
#include "materials/material_parameters.h"
#include "materials/scattered.h"

namespace rtiow {

struct Dielectric {
  float ior = 1.5f;  // index of refraction inside, relative to outside
  FresnelModel fresnel = FresnelModel::Schlick;

  static constexpr const char* kType = "dielectric";
  static constexpr const char* kDoc =
      "glass, water, a bubble: reflects or refracts, absorbs nothing";
  // The index within the range the extremes tests render without NaN (core/limits/input_limits.h).
  static constexpr auto parameters() {
    return std::tuple{
        NumberParameter<Dielectric>{"ior", &Dielectric::ior, std::nullopt, float(limits::kMinIor),
                                    float(limits::kMaxIor), false,
                                    "the index of refraction inside, relative to outside"},
        ChoiceParameter<Dielectric, FresnelModel, 2>{
            "fresnel",
            &Dielectric::fresnel,
            FresnelModel::Schlick,
            {FresnelModel::Schlick, FresnelModel::Exact},
            "the reflectance: the book's Schlick approximation or exact Fresnel"}};
  }
};

// The bounce dimensions scatter reads.
constexpr unsigned bounce_uses(const Dielectric&) {
  return kUsesLobe;
}

inline std::optional<Scattered> scatter(const Dielectric& m, const Vec3& in_direction,
                                        const SurfaceHit& hit, const BounceSample& u) {
  const Color white{1.0f, 1.0f, 1.0f};  // glass absorbs nothing
  const float eta = hit.front_face ? 1.0f / m.ior : m.ior;
  const Vec3 unit = normalize(in_direction);
  const float cos_theta = std::min(dot(-unit, hit.normal), 1.0f);
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  const bool total_internal_reflection = eta * sin_theta > 1.0f;
  // Index 1 is no interface at all: Schlick's formula would still reflect (1-cos)^5 at grazing
  // angles and draw a rim around an invisible sphere.
  float reflectance = 0.0f;
  if (m.ior != 1.0f) {
    reflectance = m.fresnel == FresnelModel::Exact ? exact_reflectance(cos_theta, eta)
                                                   : schlick_reflectance(cos_theta, eta);
  }
  if (total_internal_reflection || reflectance > u.lobe)
    return Scattered{reflect(unit, hit.normal), white};
  return Scattered{refract(unit, hit.normal, eta), white};
}

}  // namespace rtiow
