// The Sobol sampler: each dimension's power-of-two prefixes fill their strata, the first
// two dimensions form a (0,2)-sequence, scrambling keeps both, and a pixel sample's numbers
// are a pure function of (seed, pixel, sample) whichever sampler draws them.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "core/sampling/sampler.h"
#include "core/sampling/sobol.h"
#include "tests/stream_draws.h"

namespace rtiow {
namespace {

// True if the first 2^m values put exactly one point in each interval [k/2^m, (k+1)/2^m).
bool fills_strata(const std::vector<float>& values, int m) {
  const std::size_t n = std::size_t(1) << m;
  std::vector<int> hits(n, 0);
  for (std::size_t i = 0; i < n; ++i) ++hits[std::size_t(values[i] * float(n))];
  for (const int h : hits) {
    if (h != 1) return false;
  }
  return true;
}

TEST(Sobol, EveryDimensionFillsItsStrataAtEveryPowerOfTwo) {
  for (int d = 0; d < kSobolDimensions; ++d) {
    for (const std::uint32_t seed : {0u, 0x12345678u, 0xdeadbeefu}) {
      std::vector<float> values;
      for (std::uint32_t i = 0; i < 1024; ++i) {
        values.push_back(seed == 0 ? float(sobol_bits(i, d) >> 8) * 0x1p-24f
                                   : scrambled_sobol(i, d, seed));
      }
      for (int m = 0; m <= 10; ++m) {
        EXPECT_TRUE(fills_strata(values, m)) << "dimension " << d << " seed " << seed << " m " << m;
      }
    }
  }
}

TEST(Sobol, FirstTwoDimensionsAreAZeroTwoSequenceScrambledOrNot) {
  constexpr int m = 8;
  constexpr std::uint32_t n = 1u << m;
  for (const std::uint32_t seed : {0u, 7u, 0x9e3779b9u}) {
    // Every elementary interval of area 2^-m (2^k by 2^(m-k) cells) holds one point.
    for (int k = 0; k <= m; ++k) {
      std::set<std::uint32_t> cells;
      for (std::uint32_t i = 0; i < n; ++i) {
        const float x =
            seed == 0 ? float(sobol_bits(i, 0) >> 8) * 0x1p-24f : scrambled_sobol(i, 0, seed);
        const float y = seed == 0 ? float(sobol_bits(i, 1) >> 8) * 0x1p-24f
                                  : scrambled_sobol(i, 1, seed ^ 0x5555u);
        const auto cx = std::uint32_t(x * float(1u << k)),
                   cy = std::uint32_t(y * float(1u << (m - k)));
        cells.insert(cx << (m - k) | cy);
      }
      EXPECT_EQ(cells.size(), n) << "k = " << k << " seed " << seed;
    }
  }
}

TEST(Sobol, ScramblingIsUniformAcrossSeeds) {
  // One point under many scrambles is uniform: the mean of 20000 is 0.5 within 5 sigma.
  for (int d = 0; d < kSobolDimensions; ++d) {
    double sum = 0;
    constexpr int kSeeds = 20000;
    for (int s = 0; s < kSeeds; ++s) {
      sum += scrambled_sobol(3, d, std::uint32_t(mix64(std::uint64_t(s)) >> 32));
    }
    EXPECT_NEAR(sum / kSeeds, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / kSeeds)) << "dimension " << d;
  }
}

using test::draws;

TEST(SobolSampleStream, IsAPureFunctionOfSeedPixelAndSample) {
  std::vector<std::vector<float>> forward;
  for (std::uint64_t s = 0; s < 32; ++s) forward.push_back(draws(SampleStream(7, 3, 4, s, 8), 12));
  for (int s = 31; s >= 0; --s) {
    EXPECT_EQ(draws(SampleStream(7, 3, 4, std::uint64_t(s), 8), 12), forward[std::size_t(s)]);
  }
  EXPECT_NE(draws(SampleStream(8, 3, 4, 0, 8), 12), forward[0]);
  EXPECT_NE(draws(SampleStream(7, 4, 3, 0, 8), 12), forward[0]);
}

TEST(SobolSampleStream, PixelDimensionsFillStrataAndLaterOnesComeFromTheStream) {
  std::vector<float> x, y;
  for (std::uint64_t s = 0; s < 256; ++s) {
    SampleStream stream(5, 10, 20, s, 4);
    x.push_back(stream.next_1d());
    y.push_back(stream.next_1d());
    stream.skip(2);
    // Past the Sobol dimensions: the independent stream's numbers, as without Sobol.
    SampleStream independent(5, 10, 20, s);
    EXPECT_EQ(stream.next_1d(), independent.next_1d());
  }
  for (int m = 0; m <= 8; ++m) {
    EXPECT_TRUE(fills_strata(x, m)) << m;
    EXPECT_TRUE(fills_strata(y, m)) << m;
  }
}

// Each dimension has its own scramble: over many pixels, no two Sobol dimensions of a sample
// are correlated. At sample 0 every Sobol dimension's unscrambled point is 0, so the values
// there are the scrambles themselves; two dimensions that shared one would be equal (r = 1).
// Under independence r has a standard deviation of 1/64 here: |r| < 0.1 is over 6 of them.
TEST(SobolSampleStream, EveryDimensionHasItsOwnScramble) {
  constexpr int kPixels = 4096;
  for (std::uint64_t sample : {0u, 1u, 5u}) {
    std::vector<std::vector<double>> values(kSobolDimensions);
    for (std::uint32_t p = 0; p < kPixels; ++p) {
      SampleStream stream(11, p % 64, p / 64, sample, kSobolDimensions);
      for (int d = 0; d < kSobolDimensions; ++d) values[std::size_t(d)].push_back(stream.next_1d());
    }
    const auto correlation = [](const std::vector<double>& a, const std::vector<double>& b) {
      const double n = double(a.size());
      double ma = 0, mb = 0;
      for (std::size_t i = 0; i < a.size(); ++i) ma += a[i] / n, mb += b[i] / n;
      double ab = 0, aa = 0, bb = 0;
      for (std::size_t i = 0; i < a.size(); ++i) {
        ab += (a[i] - ma) * (b[i] - mb), aa += (a[i] - ma) * (a[i] - ma);
        bb += (b[i] - mb) * (b[i] - mb);
      }
      return ab / std::sqrt(aa * bb);
    };
    for (int d = 0; d < kSobolDimensions; ++d) {
      for (int e = d + 1; e < kSobolDimensions; ++e) {
        EXPECT_LT(std::abs(correlation(values[std::size_t(d)], values[std::size_t(e)])), 0.1)
            << "dimensions " << d << " and " << e << " at sample " << sample;
      }
    }
  }
}

TEST(SobolSampleStream, IndependentModeIsTheBooksSampler) {
  // Zero Sobol dimensions: the same numbers as before the Sobol sampler existed.
  EXPECT_EQ(draws(SampleStream(3, 1, 2, 9, 0), 16), draws(SampleStream(3, 1, 2, 9), 16));
}

}  // namespace
}  // namespace rtiow
