#pragma once
// What the renderer asks of an accelerator, written down: built over a scene's spheres, it
// names itself and returns the closest hit with 0 < t < t_max, or nothing, leaving out the
// sphere `skip` (the one a ray leaves outward, which it cannot hit again) unless that is
// kNoSphere. EmbreeAccel
// (a BVH) and NaiveAccel (a loop) both satisfy it and both call the one sphere test, so they
// return the same hits bit for bit; test doubles in the benchmark and the tests do too.

#include <concepts>
#include <cstdint>
#include <optional>

#include "core/geometry/hit.h"
#include "core/geometry/ray.h"

namespace rtiow {

template <typename A>
concept Accelerator = requires(const A& accel, const Ray& ray, float t_max, std::uint32_t skip) {
  { accel.intersect(ray, t_max, skip) } -> std::same_as<std::optional<Hit>>;
};

}  // namespace rtiow
