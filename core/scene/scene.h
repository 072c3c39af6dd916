#pragma once
// A scene: what the renderer models and nothing more. Spheres with materials, a
// background, a camera, and the image settings the scene was composed for.

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/sphere_set.h"
#include "core/scene/background.h"
#include "core/scene/camera.h"
#include "materials/material.h"

namespace rtiow {

struct ImageSettings {
  int width = 400;
  double aspect_ratio = 16.0 / 9.0;  // height = round(width / aspect_ratio) unless given
  int samples_per_pixel = 100;
  int max_depth = 50;
};

// The one aspect rule: the side not given follows from the other and the aspect ratio
// (width / height), rounded to the nearest pixel. Unchecked: callers check the range.
inline double height_for_width(int width, double aspect_ratio) {
  return std::round(double(width) * (1.0 / aspect_ratio));
}
inline double width_for_height(int height, double aspect_ratio) {
  return std::round(double(height) * aspect_ratio);
}

struct Scene {
  std::string name;
  std::optional<std::uint64_t> layout_seed;  // provenance of a randomly generated layout
  SphereSet spheres;
  std::vector<Material> materials;
  Background background;
  CameraSettings camera;
  ImageSettings image;

  std::uint32_t add_material(const Material& m) {
    materials.push_back(m);
    return static_cast<std::uint32_t>(materials.size() - 1);
  }
};

// Throws InvalidInput naming what is wrong: no spheres, a non-finite or zero radius, a
// missing material, a material parameter out of range, a degenerate camera.
void validate(const Scene& scene);

}  // namespace rtiow
