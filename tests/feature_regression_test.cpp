// The denoiser's second pass (core/denoise/feature_regression.h) is filtered in tiles of columns
// so that its patch terms stay in cache; where the tiles fall must change no bit.

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/denoise/feature_regression.h"

namespace rtiow {
namespace {

// An image of random values and features, sky (depth 0) in some pixels, and a guide with a
// variance of its own: what the pass weighs and fits needs no meaning to be compared.
struct Scrambled {
  DenoiseInput in;
  std::vector<Vec3d> guide_variance;

  Scrambled(int width, int height, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    in.width = width, in.height = height;
    for (int p = 0; p < width * height; ++p) {
      const float depth = p % 5 == 0 ? 0.0f : 1.0f + 8.0f * u(rng);
      in.features.push_back({u(rng), u(rng), u(rng), u(rng), -u(rng), u(rng), depth});
      in.even.push_back({u(rng), 2.0f * u(rng), 0.05f * u(rng)});
      in.odd.push_back({u(rng), u(rng), u(rng)});
      in.mean.push_back((in.even.back() + in.odd.back()) * 0.5f);
      in.even_samples.push_back(3), in.odd_samples.push_back(3);
      guide_variance.push_back({0.01 * u(rng), 0.02 * u(rng), 0.001 + 0.01 * u(rng)});
    }
  }
};

TEST(FeatureRegression, TheSameBitsWhereverItsTilesOfColumnsFall) {
  const Scrambled s(70, 13, 5);
  const Guide guide{&s.in.odd, &s.guide_variance};
  const std::vector<Weighting> weightings{{0.5f, Fit::kRegression}, {2.0f, Fit::kMean}};
  // One tile wider than the image: nothing is cut.
  const std::vector<FilteredHalf> whole = filter_half(s.in, s.in.even, guide, weightings, {}, 72);
  for (const int tile : {4, 8, 12, 64, kColumnsPerTile}) {
    const std::vector<FilteredHalf> tiled =
        filter_half(s.in, s.in.even, guide, weightings, {}, tile);
    ASSERT_EQ(tiled.size(), whole.size());
    for (std::size_t k = 0; k < whole.size(); ++k) {
      EXPECT_EQ(tiled[k].color, whole[k].color) << "tiles of " << tile << ", weighting " << k;
      EXPECT_EQ(tiled[k].own_weight, whole[k].own_weight) << "tiles of " << tile;
    }
  }
  EXPECT_THROW(filter_half(s.in, s.in.even, guide, weightings, {}, 6), std::invalid_argument);
}

}  // namespace
}  // namespace rtiow
