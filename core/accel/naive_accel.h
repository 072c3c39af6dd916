#pragma once
// The book's intersector done properly: a linear loop over every sphere, reading the
// structure-of-arrays directly and calling the same sphere test as the Embree callback.
// It is the honest baseline Embree is measured against, and the reference for its hits.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>

#include "core/geometry/hit.h"
#include "core/geometry/ray.h"
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
  // (core/accel/naive_accel.cpp, compiled for each instruction set.)
  std::optional<Hit> intersect(const Ray& ray, float t_max, std::uint32_t skip = kNoSphere) const;

 private:
  const SphereSet* spheres_;
};

}  // namespace rtiow
