// The spawned ray's rounding step, written as selects on the bits, against the C library.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/geometry/ray_offset.h"

namespace rtiow {
namespace {

TEST(NextFloatToward, IsNextafterForEveryKindOfFloat) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const std::vector<float> values = {0.0f,
                                     -0.0f,
                                     std::numeric_limits<float>::denorm_min(),
                                     -std::numeric_limits<float>::denorm_min(),
                                     std::numeric_limits<float>::min(),
                                     -std::numeric_limits<float>::min(),
                                     1.0f,
                                     -1.0f,
                                     0.5f,
                                     -1000.0f,
                                     3.0e-39f,
                                     std::numeric_limits<float>::max(),
                                     -std::numeric_limits<float>::max(),
                                     kInf,
                                     -kInf};
  for (const float v : values) {
    for (const bool up : {true, false}) {
      const float expected = std::nextafter(v, up ? kInf : -kInf);
      const float got = next_float_toward(v, up);
      EXPECT_EQ(std::bit_cast<std::uint32_t>(got), std::bit_cast<std::uint32_t>(expected))
          << v << (up ? " up" : " down");
    }
  }
}

TEST(NextFloatToward, IsNextafterOnRandomBits) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  std::uint32_t x = 12345u;
  for (int i = 0; i < 100000; ++i) {
    x = x * 1664525u + 1013904223u;  // every bit pattern class, NaNs aside
    const float v = std::bit_cast<float>(x);
    if (std::isnan(v)) continue;
    const bool up = (x >> 7) & 1u;
    ASSERT_EQ(std::bit_cast<std::uint32_t>(next_float_toward(v, up)),
              std::bit_cast<std::uint32_t>(std::nextafter(v, up ? kInf : -kInf)))
        << v << (up ? " up" : " down");
  }
}

}  // namespace
}  // namespace rtiow
