#pragma once
// The first n numbers a sample stream draws, for comparing streams in tests.

#include <vector>

#include "core/sampling/sampler.h"

namespace rtiow::test {

inline std::vector<float> draws(SampleStream s, int n) {
  std::vector<float> v;
  for (int i = 0; i < n; ++i) v.push_back(s.next_1d());
  return v;
}

}  // namespace rtiow::test
