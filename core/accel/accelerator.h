#pragma once
// What the renderer asks of an accelerator, written down: built over a scene's spheres, it
// names itself and returns the closest hit with 0 < t < t_max, or nothing, leaving out the
// sphere `skip` (the one a ray leaves outward, which it cannot hit again) unless that is
// kNoSphere. EmbreeAccel
// (a BVH) and NaiveAccel (a loop) both satisfy it and both call the one sphere test, so they
// return the same hits bit for bit; test doubles in the benchmark and the tests do too.

#include <concepts>
#include <cstdint>
#include <limits>
#include <optional>

#include "core/geometry/hit.h"
#include "core/geometry/ray.h"

namespace rtiow {

template <typename A>
concept Accelerator = requires(const A& accel, const Ray& ray, float t_max, std::uint32_t skip) {
  { accel.intersect(ray, t_max, skip) } -> std::same_as<std::optional<Hit>>;
};

// How many coherent rays (a pixel's camera rays) go to an accelerator at once.
inline constexpr int kRayPacketSize = 8;

// The closest hits (0 < t < infinity) of `count` <= kRayPacketSize rays: through the
// accelerator's packet query where it has one (Embree's rtcIntersect8), one by one otherwise.
// Either way the hits are those of intersect(), bit for bit.
template <Accelerator A>
void intersect_packet(const A& accel, const Ray* rays, int count, std::optional<Hit>* hits) {
  if constexpr (requires { accel.intersect_packet(rays, count, hits); }) {
    accel.intersect_packet(rays, count, hits);
  } else {
    for (int k = 0; k < count; ++k) {
      hits[k] = accel.intersect(rays[k], std::numeric_limits<float>::infinity(), kNoSphere);
    }
  }
}

}  // namespace rtiow
