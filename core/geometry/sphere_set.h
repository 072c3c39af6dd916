#pragma once
// All spheres of a scene, structure-of-arrays: the naive loop streams through the
// coordinates it needs and the Embree callback reads one sphere by index.

#include <cstdint>
#include <vector>

#include "core/geometry/vec3.h"

namespace rtiow {

struct SphereSet {
  std::vector<float> center_x, center_y, center_z, radius;
  std::vector<std::uint32_t> material;

  std::size_t size() const { return radius.size(); }

  void add(const Vec3& center, float r, std::uint32_t material_index) {
    center_x.push_back(center.x);
    center_y.push_back(center.y);
    center_z.push_back(center.z);
    radius.push_back(r);
    material.push_back(material_index);
  }

  void reserve(std::size_t n) {
    center_x.reserve(n), center_y.reserve(n), center_z.reserve(n);
    radius.reserve(n), material.reserve(n);
  }

  Vec3 center(std::size_t i) const { return {center_x[i], center_y[i], center_z[i]}; }
};

}  // namespace rtiow
