// The one validator of a pixel's sums (core/film/sum_validation.h): every pixel that samples
// can make passes, at the extremes of the values and counts too; every change that no samples
// can make is refused, naming the channel.

#include "core/film/sum_validation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include "core/film/replicate_variance.h"

namespace rtiow {
namespace {

struct Pixel {
  PixelSum sum;
  PixelSpread spread;
  FirstHitSum first_hit;
  PixelSumsRef ref() const { return {&sum, &spread, &first_hit}; }
};

// `n` samples from index `first`, each drawn by `value` (per channel) and hitting a surface
// with probability 1/2 (a unit normal, an albedo in [0, 1], a depth).
template <typename Value>
Pixel sampled(std::uint64_t first, std::uint64_t n, std::mt19937_64& rng, Value value) {
  Pixel p;
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), signed_unit(-1.0f, 1.0f);
  for (std::uint64_t i = first; i < first + n; ++i) {
    add_sample(p.sum, p.spread, Color{value(rng), value(rng), value(rng)}, i);
    if (unit(rng) < 0.5f) {
      const Vec3 direction{signed_unit(rng), signed_unit(rng), signed_unit(rng)};
      const float length = std::sqrt(dot(direction, direction));
      const Vec3 normal = length > 1e-3f ? direction / length : Vec3{0, 1, 0};
      p.first_hit.add({Color{unit(rng), unit(rng), 1.0f}, normal, 1e3f * unit(rng)});
    } else {
      p.first_hit.add({});
    }
  }
  return p;
}

TEST(SumValidation, EverySampledPixelPasses) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const auto bright = [&](std::mt19937_64& r) { return 1e4f * unit(r); };
  const auto tiny = [&](std::mt19937_64& r) { return 1e-6f * unit(r); };  // squares round to 0
  const auto constant = [](std::mt19937_64&) { return 0.3f; };
  const auto beyond = [](std::mt19937_64&) { return 1e12f; };  // clamped to the most a sample is
  const auto rare = [&](std::mt19937_64& r) { return unit(r) < 0.01f ? 500.0f : 0.0f; };
  const auto nonsense = [&](std::mt19937_64& r) {  // NaN and infinities count as 0
    const float u = unit(r);
    return u < 0.3f ? NAN : u < 0.6f ? INFINITY : u;
  };
  int checked = 0;
  for (const std::uint64_t first : {0ull, 1ull, 7ull}) {
    for (const std::uint64_t n : {1ull, 2ull, 3ull, 17ull, 400ull}) {
      for (int trial = 0; trial < 20; ++trial) {
        for (const Pixel& p : {sampled(first, n, rng, [&](auto& r) { return unit(r); }),
                               sampled(first, n, rng, bright), sampled(first, n, rng, tiny),
                               sampled(first, n, rng, constant), sampled(first, n, rng, beyond),
                               sampled(first, n, rng, rare), sampled(first, n, rng, nonsense)}) {
          EXPECT_EQ(impossible_sums(p.ref(), first, n), "") << "first " << first << ", n " << n;
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, 3 * 5 * 20 * 7);
  // No samples: all zero.
  EXPECT_EQ(impossible_sums(Pixel{}.ref(), 0, 0), "");
  // A part written before spreads, and a render without passes, keep fewer groups.
  const Pixel p = sampled(0, 8, rng, bright);
  EXPECT_EQ(impossible_sums({&p.sum, nullptr, nullptr}, 0, 8), "");
}

// `change` applied to an honest pixel of 4 samples from index 0 (values about 1) is refused,
// in words that hold `expected`.
template <typename Change>
void expect_refused(const char* what, Change change, const std::string& expected) {
  SCOPED_TRACE(what);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<float> around_one(0.5f, 1.5f);
  Pixel p = sampled(0, 4, rng, [&](auto& r) { return around_one(r); });
  ASSERT_EQ(impossible_sums(p.ref(), 0, 4), "");
  change(p);
  const std::string why = impossible_sums(p.ref(), 0, 4);
  EXPECT_NE(why.find(expected), std::string::npos) << "got: '" << why << "'";
}

constexpr int128 kOne = int128(1) << 32;  // 1.0 in the sums' fixed point

TEST(SumValidation, EveryImpossibleChangeIsRefusedByName) {
  expect_refused(
      "a sum beyond its samples", [](Pixel& p) { p.sum.set_channel(1, int128(1) << 100); },
      "sum.G is beyond what 4 samples can add up to");
  expect_refused(
      "a negative sum", [](Pixel& p) { p.sum.set_channel(0, -1); }, "sum.R is beyond");
  expect_refused(
      "a replicate's sum beyond its samples",
      [](Pixel& p) { p.spread.odd.set_channel(2, 3 * (kOne << 30)); },
      "odd.B is beyond what 2 samples of odd index can add up to");
  expect_refused(
      "the replicate's sum above the samples'",
      [](Pixel& p) { p.spread.odd.set_channel(0, p.sum.channel(0) + 1); },
      "odd.R is more than sum.R");
  expect_refused(
      "a sum raised within range, its squares not",
      [](Pixel& p) { p.sum.set_channel(2, p.sum.channel(2) + 50 * kOne); },
      "squares.B is less than the squares of samples whose sum is sum.B can add up to");
  expect_refused(
      "squares lowered", [](Pixel& p) { p.spread.squares.set_channel(1, kOne); },
      "squares.G is less");
  expect_refused(
      "squares raised past what the sum can square to",
      [](Pixel& p) { p.spread.squares.set_channel(0, kOne << 34); }, "squares.R is more");
  expect_refused(
      "an albedo beyond one a sample", [](Pixel& p) { p.first_hit.set_channel(1, 5 * kOne); },
      "first_hit.albedo.G is beyond what 4 samples can add up to");
  expect_refused(
      "a negative depth", [](Pixel& p) { p.first_hit.set_channel(6, -kOne); },
      "first_hit.Z is beyond");
  expect_refused(
      "normals longer than their samples",
      [](Pixel& p) {
        for (std::size_t c = 3; c < 6; ++c) p.first_hit.set_channel(c, 4 * kOne);
      },
      "first_hit.N is longer than 4 samples of unit normals");
}

TEST(SumValidation, ACountThatDoesNotHoldTheSamplesIsRefused) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> around_one(0.5f, 1.5f);
  const Pixel p = sampled(0, 4, rng, [&](auto& r) { return around_one(r); });
  // Told fewer samples than were added: one from index 0 has no odd sample.
  EXPECT_NE(impossible_sums(p.ref(), 0, 1).find("odd.R is beyond what 0 samples of odd index"),
            std::string::npos);
  // Told they start at another index: the replicates no longer match their counts.
  const Pixel q = sampled(1, 1, rng, [&](auto& r) { return around_one(r); });
  EXPECT_NE(impossible_sums(q.ref(), 0, 1), "");
  EXPECT_EQ(impossible_sums(q.ref(), 1, 1), "");
}

}  // namespace
}  // namespace rtiow
