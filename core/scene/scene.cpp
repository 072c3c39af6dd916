#include "core/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/io/error.h"
#include "core/io/input_limits.h"

namespace rtiow {
namespace {

bool in_unit_range(const Color& c) {
  return is_finite(c) && c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x <= 1 && c.y <= 1 && c.z <= 1;
}

std::string sphere_name(std::size_t i) {
  return "scene: sphere " + std::to_string(i) + ": ";
}

}  // namespace

void validate(const Scene& scene) {
  const SphereSet& s = scene.spheres;
  if (s.size() == 0) throw InvalidInput("scene: it has no spheres");
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Vec3 c = s.center(i);
    const double extent = std::max({std::abs(double(c.x)), std::abs(double(c.y)),
                                    std::abs(double(c.z)), std::abs(double(s.radius[i]))});
    if (!is_finite(c) || !std::isfinite(s.radius[i]) || extent > limits::kMaxCoordinate) {
      throw InvalidInput(sphere_name(i) + "centre and radius must be finite and within +-1e15");
    }
    // A zero radius would give the hit no normal (0/0); it would be invisible anyway.
    if (s.radius[i] == 0.0f) throw InvalidInput(sphere_name(i) + "radius must not be 0");
    if (s.material[i] >= scene.materials.size()) {
      throw InvalidInput(sphere_name(i) + "refers to a material that does not exist");
    }
  }
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const std::string where = "scene: material " + std::to_string(i) + ": ";
    const Material& m = scene.materials[i];
    if (const auto* l = std::get_if<Lambertian>(&m); l && !in_unit_range(l->albedo)) {
      throw InvalidInput(where + "albedo must be in [0, 1]");
    }
    if (const auto* metal = std::get_if<Metal>(&m)) {
      if (!in_unit_range(metal->albedo)) throw InvalidInput(where + "albedo must be in [0, 1]");
      if (!(metal->fuzz >= 0.0f && metal->fuzz <= 1.0f)) {
        throw InvalidInput(where + "fuzz must be in [0, 1]");
      }
    }
    if (const auto* d = std::get_if<Dielectric>(&m);
        d && !(d->ior >= limits::kMinIor && d->ior <= limits::kMaxIor)) {
      throw InvalidInput(where + "index of refraction must be from 0.001 to 1e6");
    }
  }
  if (!is_finite(scene.background.horizon) || !is_finite(scene.background.zenith) ||
      std::min({scene.background.horizon.x, scene.background.horizon.y, scene.background.horizon.z,
                scene.background.zenith.x, scene.background.zenith.y, scene.background.zenith.z}) <
          0.0f) {
    throw InvalidInput("scene: background colours must be finite and >= 0");
  }
  validate(scene.camera);
}

}  // namespace rtiow
