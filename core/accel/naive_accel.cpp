#include "core/accel/naive_accel.h"

#include <algorithm>
#include <limits>

#include "core/geometry/sphere_intersect.h"
#include "core/parallel/instruction_sets.h"

namespace rtiow {

namespace {

// The loop, cloned for each instruction set. File-local: a cloned function declared in a
// header without the attribute is an ODR mismatch to GCC's link-time optimiser.
RTIOW_DISPATCHED std::optional<Hit> closest_hit(const SphereSet& s, const Ray& ray, float t_max,
                                                std::uint32_t skip) {
  constexpr std::size_t kBlock = 256;
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
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

}  // namespace

std::optional<Hit> NaiveAccel::intersect(const Ray& ray, float t_max, std::uint32_t skip) const {
  return closest_hit(*spheres_, ray, t_max, skip);
}

}  // namespace rtiow
