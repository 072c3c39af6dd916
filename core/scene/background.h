#pragma once
// What a ray that leaves the scene sees: the book's vertical sky gradient, or a uniform
// colour when both ends are equal (the white furnace).

#include "core/geometry/vec3.h"

namespace rtiow {

struct Background {
  Color horizon{1.0f, 1.0f, 1.0f};
  Color zenith{0.5f, 0.7f, 1.0f};

  Color operator()(const Vec3& direction) const {
    const float t = 0.5f * (normalize(direction).y + 1.0f);
    return (1.0f - t) * horizon + t * zenith;
  }
};

}  // namespace rtiow
