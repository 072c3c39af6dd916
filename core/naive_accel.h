#pragma once
// The book's intersector done properly: a linear loop over every sphere, reading the
// structure-of-arrays directly and calling the same sphere test as the Embree callback.
// It is the honest baseline Embree is measured against, and the reference for its hits.

#include <limits>

#include "core/hit.h"
#include "core/sphere_intersect.h"
#include "core/sphere_set.h"

namespace rtiow {

class NaiveAccel {
 public:
  explicit NaiveAccel(const SphereSet& spheres) : spheres_(&spheres) {}

  static constexpr const char* name() { return "naive"; }

  // Closest hit with 0 < t < t_max.
  bool intersect(const Ray& ray, float t_max, Hit& hit) const {
    const SphereSet& s = *spheres_;
    const std::size_t n = s.size();
    float closest = t_max;
    std::uint32_t found = kNone;
    for (std::size_t i = 0; i < n; ++i) {
      float t;
      const Vec3 c{s.center_x[i], s.center_y[i], s.center_z[i]};
      if (intersect_sphere(c, s.radius[i], ray, 0.0f, closest, t)) {
        closest = t;
        found = static_cast<std::uint32_t>(i);
      }
    }
    if (found == kNone) return false;
    hit = Hit{closest, found};
    return true;
  }

  // Any hit with 0 < t < t_max.
  bool occluded(const Ray& ray, float t_max) const {
    const SphereSet& s = *spheres_;
    for (std::size_t i = 0; i < s.size(); ++i) {
      float t;
      if (intersect_sphere(s.center(i), s.radius[i], ray, 0.0f, t_max, t)) return true;
    }
    return false;
  }

 private:
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  const SphereSet* spheres_;
};

}  // namespace rtiow
