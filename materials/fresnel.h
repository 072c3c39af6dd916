#pragma once
// Fresnel reflectance of a dielectric interface.

namespace rtiow {

// Schlick's approximation, as the book uses it. `eta` is the ratio of the two indices;
// R0 is the same for eta and 1/eta.
inline float schlick_reflectance(float cos_theta, float eta) {
  float r0 = (1.0f - eta) / (1.0f + eta);
  r0 = r0 * r0;
  const float m = 1.0f - cos_theta;
  const float m2 = m * m;
  return r0 + (1.0f - r0) * (m2 * m2 * m);
}

}  // namespace rtiow
