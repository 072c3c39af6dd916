#pragma once
// The book's intersector done properly: a linear loop over every sphere, reading the
// structure-of-arrays directly and calling the same sphere test as the Embree callback.
// It is the honest baseline Embree is measured against, and the reference for its hits.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "core/geometry/hit.h"
#include "core/geometry/sphere_intersect.h"
#include "core/geometry/sphere_set.h"

namespace rtiow {

class NaiveAccel {
 public:
  explicit NaiveAccel(const SphereSet& spheres) : spheres_(&spheres) {}

  static constexpr const char* name() { return "naive"; }

  // Closest hit with 0 < t < t_max. Spheres go in blocks: a branch-free pass that the
  // compiler vectorises marks the few spheres whose line the ray comes near
  // (sphere_line_may_hit), then the full sphere test runs on those alone. The answer is the one
  // a sphere-by-sphere loop gives, bit for bit.
  std::optional<Hit> intersect(const Ray& ray, float t_max, std::uint32_t skip = kNoSphere) const {
    const SphereSet& s = *spheres_;
    const std::size_t n = s.size();
    float closest = t_max;
    std::uint32_t found = kNone;
    alignas(64) unsigned char candidate[kBlock];
    for (std::size_t begin = 0; begin < n; begin += kBlock) {
      const std::size_t count = std::min(kBlock, n - begin);
      const float* cx = s.center_x.data() + begin;
      const float* cy = s.center_y.data() + begin;
      const float* cz = s.center_z.data() + begin;
      const float* radius = s.radius.data() + begin;
      for (std::size_t i = 0; i < count; ++i) {
        candidate[i] = sphere_line_may_hit(Vec3{cx[i], cy[i], cz[i]}, radius[i], ray);
      }
      for (std::size_t i = 0; i < count; ++i) {
        if (!candidate[i] || begin + i == skip) continue;
        const float t =
            sphere_hit_distance_exact(Vec3{cx[i], cy[i], cz[i]}, radius[i], ray, 0.0f, closest);
        if (t < closest) {
          closest = t;
          found = static_cast<std::uint32_t>(begin + i);
        }
      }
    }
    if (found == kNone) return std::nullopt;
    return Hit{closest, found};
  }

 private:
  static constexpr std::size_t kBlock = 256;
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  const SphereSet* spheres_;
};

}  // namespace rtiow
