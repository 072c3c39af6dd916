#pragma once
// A material parameter out of range: which one, which component (-1 for a number), its value
// and the rule it breaks. Each material checks its own parameters (check_parameters, in its
// file), so that a scene file and a scene built in C++ refuse the same values in the same words.

#include <cmath>
#include <optional>
#include <string>

#include "core/geometry/vec3.h"

namespace rtiow {

struct ParameterProblem {
  std::string field;
  int component = -1;
  double value = 0.0;
  std::string rule;  // "must be ..."
};

// Reflectances: each component finite and in [0, 1] (a surface returns no more than it gets).
inline std::optional<ParameterProblem> check_albedo(const Color& albedo) {
  for (int i = 0; i < 3; ++i) {
    const float c = albedo[std::size_t(i)];
    if (!(c >= 0.0f && c <= 1.0f)) return ParameterProblem{"albedo", i, c, "must be in [0, 1]"};
  }
  return std::nullopt;
}

}  // namespace rtiow
