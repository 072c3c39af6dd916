#pragma once
// A ray: origin and direction (not necessarily unit length).

#include "core/vec3.h"

namespace rtiow {

template <typename T>
struct RayT {
  Vec3T<T> origin;
  Vec3T<T> direction;

  constexpr Vec3T<T> at(T t) const { return origin + t * direction; }
};

using Ray = RayT<float>;
using Rayd = RayT<double>;

}  // namespace rtiow
