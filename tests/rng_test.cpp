#include "core/sampling/sampler.h"
#include "tests/stream_draws.h"

#include <gtest/gtest.h>

#include <set>
#include <vector>

namespace rtiow {
namespace {

using test::draws;

TEST(SampleStream, IsAPureFunctionOfSeedPixelAndSample) {
  // Visit (pixel, sample) pairs forwards and backwards: the values must not depend on order.
  std::vector<std::vector<float>> forward;
  for (std::uint32_t s = 0; s < 16; ++s) forward.push_back(draws(SampleStream(7, 3, 4, s), 8));
  for (int s = 15; s >= 0; --s) {
    EXPECT_EQ(draws(SampleStream(7, 3, 4, std::uint64_t(s)), 8), forward[std::size_t(s)]);
  }
}

TEST(SampleStream, DiffersAcrossSeedsPixelsAndSamples) {
  const auto base = draws(SampleStream(1, 10, 20, 0), 4);
  EXPECT_NE(draws(SampleStream(2, 10, 20, 0), 4), base);
  EXPECT_NE(draws(SampleStream(1, 11, 20, 0), 4), base);
  EXPECT_NE(draws(SampleStream(1, 10, 21, 0), 4), base);
  EXPECT_NE(draws(SampleStream(1, 20, 10, 0), 4), base) << "x and y must not be symmetric";
  EXPECT_NE(draws(SampleStream(1, 10, 20, 1), 4), base);
}

TEST(SampleStream, ValuesLieInTheHalfOpenUnitInterval) {
  SampleStream s(3, 0, 0, 0);
  for (int i = 0; i < 100000; ++i) {
    const float u = s.next_1d();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
  }
}

TEST(Pcg32, FirstOutputsAreDistinct) {
  Pcg32 rng(42, 54);
  std::set<std::uint32_t> seen;
  for (int i = 0; i < 1000; ++i) seen.insert(rng.next_u32());
  EXPECT_EQ(seen.size(), 1000u);
}

}  // namespace
}  // namespace rtiow
