// The denoiser's blend of its candidates (core/denoise/candidate_blend.h): the weights are the
// least of their quadratic over the triangle, and a blend beats each of the images it blends
// where each is wrong in its own way (one noisy, one biased).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/denoise/candidate_blend.h"

namespace rtiow {
namespace {

double objective(const std::array<double, 2>& a, double m11, double m12, double m22, double b1,
                 double b2) {
  return a[0] * a[0] * m11 + 2 * a[0] * a[1] * m12 + a[1] * a[1] * m22 - 2 * a[0] * b1 -
         2 * a[1] * b2;
}

TEST(CandidateBlend, TheWeightsAreTheLeastOverTheTriangle) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int trial = 0; trial < 500; ++trial) {
    // M = L L^T: positive semidefinite; a third of the trials singular (one column of L zero).
    const double l11 = normal(rng), l21 = normal(rng), l22 = trial % 3 ? normal(rng) : 0.0;
    const double m11 = l11 * l11, m12 = l11 * l21, m22 = l21 * l21 + l22 * l22;
    const double b1 = normal(rng), b2 = normal(rng);
    const std::array<double, 2> a = simplex_minimum(m11, m12, m22, b1, b2);
    ASSERT_GE(a[0], 0.0);
    ASSERT_GE(a[1], 0.0);
    ASSERT_LE(a[0] + a[1], 1.0 + 1e-12);
    const double found = objective(a, m11, m12, m22, b1, b2);
    for (int i = 0; i <= 100; ++i)
      for (int j = 0; i + j <= 100; ++j) {
        const std::array<double, 2> grid{i / 100.0, j / 100.0};
        ASSERT_LE(found, objective(grid, m11, m12, m22, b1, b2) + 1e-9)
            << "trial " << trial << ": (" << grid[0] << ", " << grid[1] << ") is lower";
      }
  }
}

// A noisy image X of variance s^2 and a candidate biased by b with b^2 = Var(X), independent of
// X: the blend halfway has half the squared error of either; the weights, chosen from the
// neighbourhoods' estimates alone, find it.
TEST(CandidateBlend, ABlendBeatsTheNoisyAndTheBiasedImage) {
  constexpr int kWidth = 64, kHeight = 48;
  constexpr double kHalfSigma = 0.1, kTruth = 0.5;
  const double bias = kHalfSigma / std::sqrt(2.0);  // Var(X) = kHalfSigma^2 / 2
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, kHalfSigma);
  DenoiseInput in;
  in.width = kWidth, in.height = kHeight;
  std::vector<Color> biased, unfiltered;
  std::vector<float> independent, own;
  std::vector<Vec3d> variance, weight;
  for (int p = 0; p < kWidth * kHeight; ++p) {
    Color even, odd;
    for (std::size_t c = 0; c < 3; ++c)
      even[c] = float(kTruth + noise(rng)), odd[c] = float(kTruth + noise(rng));
    const Color mean = (even + odd) * 0.5f;
    in.even.push_back(even), in.odd.push_back(odd), in.mean.push_back(mean);
    in.even_samples.push_back(4), in.odd_samples.push_back(4);
    const Vec3d d = Vec3d(even) - Vec3d(odd);
    variance.push_back(d * d * 0.25);
    weight.push_back({1, 1, 1});
    const float b = float(p % 2 ? bias : -bias);
    biased.push_back({float(kTruth) + b, float(kTruth) + b, float(kTruth) + b});
    independent.push_back(0.0f);
    unfiltered.push_back(mean), own.push_back(1.0f);  // the noisy value itself, no help
  }
  const BlendedImage blended = blend_candidates(
      in, {FilteredCandidate{&biased, &independent}, FilteredCandidate{&unfiltered, &own}},
      variance, weight, 7);
  double noisy = 0, biased_error = 0, blend = 0, share = 0, estimate = 0;
  for (std::size_t p = 0; p < in.size(); ++p) {
    for (std::size_t c = 0; c < 3; ++c) {
      const auto squared = [&](float v) { return (double(v) - kTruth) * (double(v) - kTruth); };
      noisy += squared(in.mean[p][c]), biased_error += squared(biased[p][c]);
      blend += squared(blended.color[p][c]), estimate += blended.error[p][c];
    }
    share += blended.noisy_share[p];
  }
  share /= double(in.size());
  EXPECT_NEAR(share, 0.5, 0.1) << "the weights that halve the error";
  EXPECT_LT(blend, 0.6 * std::min(noisy, biased_error));
  // Its own estimate of that error: its standard error over 9,216 values is about 2%.
  EXPECT_NEAR(estimate / blend, 1.0, 0.1);
}

}  // namespace
}  // namespace rtiow
