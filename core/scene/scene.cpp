#include "core/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/parallel/cancellation.h"

namespace rtiow {
namespace {

std::string sphere_name(std::size_t i) {
  return "scene: sphere " + std::to_string(i) + ": ";
}

}  // namespace

void validate(const Scene& scene) {
  const SphereSet& s = scene.spheres;
  if (s.size() == 0) throw InvalidInput("scene: it has no spheres");
  // Millions of spheres take seconds: a stop asked for meanwhile is honoured.
  constexpr std::size_t kBetweenChecks = 1 << 16;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (i % kBetweenChecks == 0) throw_if_cancelled();
    const Vec3 c = s.center(i);
    const double extent = std::max({std::abs(double(c.x)), std::abs(double(c.y)),
                                    std::abs(double(c.z)), std::abs(double(s.radius[i]))});
    if (!is_finite(c) || !std::isfinite(s.radius[i]) || extent > limits::kMaxCoordinate) {
      throw InvalidInput(sphere_name(i) + "centre and radius must be finite and within +-1e15");
    }
    // A zero radius would give the hit no normal (0/0); it would be invisible anyway.
    if (s.radius[i] == 0.0f) throw InvalidInput(sphere_name(i) + "radius must not be 0");
    if (std::abs(s.radius[i]) < limits::kMinRadius) {
      throw InvalidInput(sphere_name(i) + "radius must be at least 1.2e-38 in size");
    }
    if (s.material[i] >= scene.materials.size()) {
      throw InvalidInput(sphere_name(i) + "refers to a material that does not exist");
    }
  }
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    if (i % kBetweenChecks == 0) throw_if_cancelled();
    if (const auto p = check_parameters(scene.materials[i])) {
      const std::string field =
          p->component < 0 ? p->field : p->field + "[" + std::to_string(p->component) + "]";
      char value[32];
      std::snprintf(value, sizeof value, "%g", p->value);
      throw InvalidInput("scene: material " + std::to_string(i) + ": " + field + " " + p->rule +
                         ", got " + value);
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
