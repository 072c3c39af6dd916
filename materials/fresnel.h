#pragma once
// Fresnel reflectance of a dielectric interface.

#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>

namespace rtiow {

// Which reflectance a dielectric uses: the book's Schlick approximation, or exact Fresnel.
enum class FresnelModel { Schlick, Exact };

inline std::string_view to_string(FresnelModel model) {
  return model == FresnelModel::Schlick ? "schlick" : "exact";
}

inline std::optional<FresnelModel> parse_fresnel(std::string_view name) {
  for (const FresnelModel model : {FresnelModel::Schlick, FresnelModel::Exact}) {
    if (name == to_string(model)) return model;
  }
  return std::nullopt;
}

// Schlick's approximation, as the book uses it. `eta` is the ratio of the two indices;
// R0 is the same for eta and 1/eta.
inline float schlick_reflectance(float cos_theta, float eta) {
  float r0 = (1.0f - eta) / (1.0f + eta);
  r0 = r0 * r0;
  const float m = 1.0f - cos_theta;
  const float m2 = m * m;
  return r0 + (1.0f - r0) * (m2 * m2 * m);
}

// Exact Fresnel reflectance of unpolarised light at a smooth dielectric interface: the mean
// of the s- and p-polarised reflectances. `cos_theta` is the cosine of the incidence angle,
// `eta` = n_incident / n_transmitted. Past the critical angle it is 1.
inline float exact_reflectance(float cos_theta, float eta) {
  const float cos_i = std::clamp(cos_theta, 0.0f, 1.0f);
  const float sin2_t = eta * eta * (1.0f - cos_i * cos_i);
  if (sin2_t >= 1.0f) return 1.0f;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  const float r_s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float r_p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_s * r_s + r_p * r_p);
}

}  // namespace rtiow
