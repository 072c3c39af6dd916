#pragma once
// What a material does with a ray that hits it: the direction it continues in and the
// fraction of light that comes back along it. A material that absorbs the ray returns none
// (std::optional<Scattered>).

#include "core/geometry/vec3.h"

namespace rtiow {

struct Scattered {
  Vec3 direction;
  Color attenuation;
};

}  // namespace rtiow
