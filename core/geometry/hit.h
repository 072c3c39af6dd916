#pragma once
// What an accelerator reports: the distance along the ray and which sphere.

#include <cstdint>

namespace rtiow {

struct Hit {
  float t;
  std::uint32_t sphere;
};

// "No sphere", where a sphere index is expected.
inline constexpr std::uint32_t kNoSphere = 0xffffffffu;

}  // namespace rtiow
