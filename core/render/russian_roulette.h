#pragma once
// Russian roulette by throughput: at the hit of ray kRouletteFromDepth and after, a path that
// carries less than kRouletteThroughput in every channel goes on with probability (its largest
// channel / kRouletteThroughput) and is weighted up by the inverse when it does. Unbiased (the
// expected image is the book's), it ends the deep paths that carry almost nothing: on the
// cover 7% less time for about 1% more squared error (docs/accuracy.md, Russian roulette).
// Its number is a dimension of the bounce's own (core/sampling/sample_layout.h).

#include <optional>

#include "core/geometry/vec3.h"

namespace rtiow {

inline constexpr int kRouletteFromDepth = 3;
inline constexpr float kRouletteThroughput = 0.2f;

// Whether the path plays at the hit of ray `depth` with this throughput.
inline bool plays_roulette(int depth, const Color& throughput) {
  return depth >= kRouletteFromDepth && max_component(throughput) < kRouletteThroughput;
}

// The throughput a playing path goes on with, given its number in [0, 1), or nothing when it
// ends. Divided by the survival rather than multiplied by its inverse, which overflows when
// the survival is a denormal; a path that carries nothing ends.
inline std::optional<Color> roulette(const Color& throughput, float number) {
  const float survival = max_component(throughput) / kRouletteThroughput;
  if (!(number < survival)) return std::nullopt;
  return throughput / survival;
}

}  // namespace rtiow
