// The samplers: each Sobol dimension's power-of-two prefixes fill their strata, the first two
// dimensions form a (0,2)-sequence, scrambling keeps both; every bounce's 1D and 2D groups
// are stratified; the layout is fixed; a pixel sample's numbers are a pure function of
// (seed, pixel, sample) whichever sampler draws them.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
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

constexpr SamplerKind kKinds[] = {SamplerKind::Independent, SamplerKind::Sobol,
                                  SamplerKind::PaddedSobol};

TEST(SampleStream, EveryKindIsAPureFunctionOfSeedPixelAndSample) {
  for (const SamplerKind kind : kKinds) {
    std::vector<std::vector<float>> forward;
    for (std::uint64_t s = 0; s < 32; ++s) {
      forward.push_back(draws(SampleStream(7, 3, 4, s, kind), 40));
    }
    for (int s = 31; s >= 0; --s) {
      EXPECT_EQ(draws(SampleStream(7, 3, 4, std::uint64_t(s), kind), 40), forward[std::size_t(s)]);
    }
    EXPECT_NE(draws(SampleStream(8, 3, 4, 0, kind), 40), forward[0]) << to_string(kind);
    EXPECT_NE(draws(SampleStream(7, 4, 3, 0, kind), 40), forward[0]) << to_string(kind);
  }
}

// The render loop makes a pixel's shared hashes once (PixelSampler); its streams must draw
// exactly what a stream made from (seed, pixel) alone draws, past the cached dimensions too.
TEST(SampleStream, APixelsSharedHashesChangeNoValue) {
  for (const SamplerKind kind : kKinds) {
    const PixelSampler pixel(kind, 9, 31, 17);
    for (std::uint64_t s = 0; s < 64; ++s) {
      SampleStream a(pixel, s), b(kind, 9, 31, 17, s);
      for (int d = 0; d < 3 * PixelSampler::kCachedDimensions; d += 2) {
        ASSERT_EQ(a.next_2d(), b.next_2d()) << to_string(kind) << " sample " << s << " dim " << d;
      }
    }
  }
}

// The layout is fixed: the camera takes 4 dimensions and every bounce 4, for every sampler,
// and a bounce's numbers are the dimensions it starts at (2D, 1D, 1D), whatever is drawn
// before them.
TEST(SampleStream, CameraAndBouncesTakeAFixedNumberOfDimensions) {
  for (const SamplerKind kind : kKinds) {
    SampleStream stream(kind, 1, 2, 3, 5);
    stream.next_camera();
    EXPECT_EQ(stream.dimension(), kCameraDimensions);
    for (int bounce = 0; bounce < 60; ++bounce) {
      const BounceSample u = stream.next_bounce();
      EXPECT_EQ(stream.dimension(), bounce_dimension(bounce + 1)) << to_string(kind);
      for (const float v : {u.lobe, u.direction[0], u.direction[1], u.radius}) {
        ASSERT_GE(v, 0.0f);
        ASSERT_LT(v, 1.0f);
      }
    }
  }
  // Independent: the bounce's numbers are the stream's next four, in layout order.
  SampleStream a(9, 1, 1, 4), b(9, 1, 1, 4);
  const BounceSample u = a.next_bounce();
  EXPECT_EQ((std::vector<float>{u.direction[0], u.direction[1], u.lobe, u.radius}), draws(b, 4));
}

// A bounce computed in part (the dimensions a material reads) has the same values there as
// the whole bounce, and the stream goes on at the same dimension.
TEST(SampleStream, PartialBouncesKeepEveryDimensionInPlace) {
  for (const SamplerKind kind : kKinds) {
    for (const unsigned uses : {unsigned(kUsesNothing), unsigned(kUsesLobe),
                                unsigned(kUsesDirection), kUsesDirection | kUsesRadius}) {
      SampleStream whole(kind, 2, 5, 6, 77), part(kind, 2, 5, 6, 77);
      whole.next_camera(), part.next_camera();
      const BounceSample a = whole.next_bounce(), b = part.next_bounce(uses);
      if (uses & kUsesLobe) {
        EXPECT_EQ(a.lobe, b.lobe);
      }
      if (uses & kUsesDirection) {
        EXPECT_EQ(a.direction[0], b.direction[0]);
        EXPECT_EQ(a.direction[1], b.direction[1]);
      }
      if (uses & kUsesRadius) {
        EXPECT_EQ(a.radius, b.radius);
      }
      EXPECT_EQ(part.dimension(), whole.dimension());
      EXPECT_EQ(whole.next_bounce().direction[0], part.next_bounce().direction[0])
          << to_string(kind) << " uses " << uses;
    }
  }
}

// True if the first 2^m points put one point in each elementary interval of area 2^-m
// (every 2^k x 2^(m-k) grid): a (0,m,2)-net.
bool is_zero_m_two_net(const std::vector<std::array<float, 2>>& points, int m) {
  const std::uint32_t n = 1u << m;
  for (int k = 0; k <= m; ++k) {
    std::set<std::uint32_t> cells;
    for (std::uint32_t i = 0; i < n; ++i) {
      const auto cx = std::uint32_t(points[i][0] * float(1u << k)),
                 cy = std::uint32_t(points[i][1] * float(1u << (m - k)));
      cells.insert(cx << (m - k) | cy);
    }
    if (cells.size() != n) return false;
  }
  return true;
}

// The joint Sobol point covers the camera and the first three bounces; every later group (and, for
// padded-sobol, every group) is a shuffled, scrambled (0,2)-sequence of its own: the first
// 2^m samples of a pixel form a (0,m,2)-net in each 2D group and fill the strata of each 1D
// dimension, at every power of two.
// Each replicate (the even samples, the odd ones) is one stratified sequence.
TEST(SampleStream, EveryGroupOfEveryBounceIsStratifiedInEachReplicate) {
  for (const SamplerKind kind : {SamplerKind::Sobol, SamplerKind::PaddedSobol}) {
    for (const int bounce : {0, 1, 2, 3, 7, 40}) {
      for (std::uint64_t replicate = 0; replicate < kReplicates; ++replicate) {
        std::vector<std::array<float, 2>> film, direction;
        std::vector<float> lobe, radius;
        for (std::uint64_t k = 0; k < 256; ++k) {
          SampleStream stream(kind, 5, 10, 20, kReplicates * k + replicate);
          const auto camera = stream.next_camera();
          film.push_back({camera[0], camera[1]});
          BounceSample u;
          for (int b = 0; b <= bounce; ++b) u = stream.next_bounce();
          direction.push_back({u.direction[0], u.direction[1]});
          lobe.push_back(u.lobe);
          radius.push_back(u.radius);
        }
        for (int m = 0; m <= 8; ++m) {
          const std::string where = to_string(kind) + " bounce " + std::to_string(bounce) +
                                    " replicate " + std::to_string(replicate) + " m " +
                                    std::to_string(m);
          EXPECT_TRUE(fills_strata(lobe, m)) << where;
          EXPECT_TRUE(fills_strata(radius, m)) << where;
          EXPECT_TRUE(is_zero_m_two_net(film, m)) << where;
          // Sobol's joint dimensions are not (0,2)-sequences pairwise; later groups are.
          if (kind == SamplerKind::PaddedSobol || bounce_dimension(bounce) >= kSobolDimensions) {
            EXPECT_TRUE(is_zero_m_two_net(direction, m)) << where;
          }
        }
      }
    }
  }
}

// The two replicates are scrambled independently: their first points differ.
TEST(SampleStream, TheReplicatesHaveTheirOwnScrambles) {
  for (const SamplerKind kind : {SamplerKind::Sobol, SamplerKind::PaddedSobol}) {
    EXPECT_NE(draws(SampleStream(7, 3, 4, 0, kind), 40), draws(SampleStream(7, 3, 4, 1, kind), 40))
        << to_string(kind);
  }
}

// Each dimension has its own scramble (and, padded, its own shuffle): over many pixels, no
// two dimensions of a sample are correlated. Two dimensions sharing a scramble at sample 0
// would be equal (r = 1). Under independence r has a standard deviation of 1/64 here:
// |r| < 0.1 is over 6 of them.
TEST(SampleStream, NoTwoDimensionsAreCorrelatedAcrossPixels) {
  constexpr int kPixels = 4096, kDimensions = 24;
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
  for (const SamplerKind kind : {SamplerKind::Sobol, SamplerKind::PaddedSobol}) {
    for (std::uint64_t sample : {0u, 1u, 5u}) {
      std::vector<std::vector<double>> values(kDimensions);
      for (std::uint32_t p = 0; p < kPixels; ++p) {
        SampleStream stream(kind, 11, p % 64, p / 64, sample);
        stream.next_camera();
        for (int d = kCameraDimensions; d < kDimensions; d += kBounceDimensions) {
          const BounceSample u = stream.next_bounce();
          values[std::size_t(d)].push_back(u.direction[0]);
          values[std::size_t(d + 1)].push_back(u.direction[1]);
          values[std::size_t(d + 2)].push_back(u.lobe);
          values[std::size_t(d + 3)].push_back(u.radius);
        }
      }
      for (int d = kCameraDimensions; d < kDimensions; ++d) {
        for (int e = d + 1; e < kDimensions; ++e) {
          EXPECT_LT(std::abs(correlation(values[std::size_t(d)], values[std::size_t(e)])), 0.1)
              << to_string(kind) << " dimensions " << d << " and " << e << " at sample " << sample;
        }
      }
    }
  }
}

}  // namespace
}  // namespace rtiow
