#pragma once
// What an accelerator reports: the distance along the ray and which sphere.

#include <cstdint>

namespace rtiow {

struct Hit {
  float t;
  std::uint32_t sphere;
};

}  // namespace rtiow
