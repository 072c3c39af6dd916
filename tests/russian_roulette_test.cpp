// Russian roulette (core/render/russian_roulette.h): the weighting is unbiased, exactly, over
// its number; it never makes a pixel infinite; it plays only where the path carries little;
// and a path that plays keeps the sample layout (its number is a dimension the material does
// not read).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "core/render/russian_roulette.h"
#include "core/sampling/sample_layout.h"
#include "materials/material.h"
#include "tests/closed_room.h"

namespace rtiow {
namespace {

// The mean over a grid of N numbers k/N (the values a sampler's 24-bit numbers take, coarser)
// of what the path goes on with, 0 where it ends: the expectation over a uniform number,
// which must be the throughput itself.
Color mean_outcome(const Color& throughput, int n) {
  double sum[3] = {0, 0, 0};
  for (int k = 0; k < n; ++k) {
    const std::optional<Color> goes_on = roulette(throughput, float(k) / float(n));
    if (!goes_on) continue;
    sum[0] += goes_on->x, sum[1] += goes_on->y, sum[2] += goes_on->z;
  }
  return Color(Vec3d{sum[0] / n, sum[1] / n, sum[2] / n});
}

TEST(RussianRoulette, KeepsTheExpectedThroughput) {
  constexpr int kNumbers = 1 << 16;
  for (const Color& t : {Color{0.1f, 0.05f, 0.0f}, Color{0.19f, 0.19f, 0.19f},
                         Color{0.001f, 0.0002f, 0.0005f}, Color{0.0f, 0.0f, 0.03f}}) {
    ASSERT_TRUE(plays_roulette(kRouletteFromDepth, t));
    const Color mean = mean_outcome(t, kNumbers);
    // The grid's rounding of the survival: at most one number in kNumbers.
    const float survival = max_component(t) / kRouletteThroughput;
    const float tolerance = 1.5f / (kNumbers * survival);
    EXPECT_NEAR(mean.x, t.x, tolerance * t.x + 1e-9f);
    EXPECT_NEAR(mean.y, t.y, tolerance * t.y + 1e-9f);
    EXPECT_NEAR(mean.z, t.z, tolerance * t.z + 1e-9f);
  }
}

TEST(RussianRoulette, PlaysOnlyLateAndWhereThePathCarriesLittle) {
  const Color little{0.1f, 0.1f, 0.1f};
  EXPECT_FALSE(plays_roulette(kRouletteFromDepth - 1, little));
  EXPECT_TRUE(plays_roulette(kRouletteFromDepth, little));
  // One channel at the threshold is enough to go on unplayed.
  EXPECT_FALSE(plays_roulette(kRouletteFromDepth, Color{0.0f, kRouletteThroughput, 0.0f}));
  EXPECT_FALSE(plays_roulette(50, Color{1.0f, 1.0f, 1.0f}));
  // A path gone NaN does not play (the sums count it as 0).
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(plays_roulette(50, Color{nan, nan, nan}));
}

TEST(RussianRoulette, NeverMakesAPathInfinite) {
  const float tiny = std::numeric_limits<float>::denorm_min();
  for (const Color& t :
       {Color{tiny, 0.0f, 0.0f}, Color{tiny, tiny, tiny}, Color{1e-38f, 5e-39f, 0.0f}}) {
    // The number 0 survives any positive survival: the largest weight there is.
    const std::optional<Color> goes_on = roulette(t, 0.0f);
    ASSERT_TRUE(goes_on.has_value());
    EXPECT_TRUE(std::isfinite(goes_on->x) && std::isfinite(goes_on->y) &&
                std::isfinite(goes_on->z));
    EXPECT_LE(max_component(*goes_on), kRouletteThroughput * 1.0001f);
  }
  EXPECT_FALSE(roulette(Color{0.0f, 0.0f, 0.0f}, 0.0f).has_value()) << "carrying nothing ends";
}

TEST(RussianRoulette, ItsNumberIsADimensionTheMaterialDoesNotRead) {
  const Material materials[] = {Lambertian{{0.5f, 0.5f, 0.5f}},
                                make_metal({0.9f, 0.9f, 0.9f}, 0.3f), make_metal({1, 1, 1}, 0.0f),
                                Dielectric{1.5f}};
  for (const Material& m : materials) {
    const unsigned uses = bounce_uses(m);
    EXPECT_EQ(roulette_use(uses) & uses, 0u);
    BounceSample u;
    u.lobe = 0.25f, u.radius = 0.75f;
    EXPECT_EQ(roulette_number(u, uses), (uses & kUsesLobe) != 0 ? 0.75f : 0.25f);
  }
}

// In a closed dark room every path plays from kRouletteFromDepth on; one that goes on through
// every bounce draws camera + D bounces, as one that never plays, and one that ends stops early.
TEST(RussianRoulette, APathThatPlaysKeepsTheSampleLayout) {
  const Scene room = closed_room(Lambertian{{0.3f, 0.3f, 0.3f}});
  const NaiveAccel accel(room.spheres);
  constexpr int kDepth = 6;
  int ended = 0, went_on = 0;
  for (const SamplerKind kind :
       {SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::PaddedSobol}) {
    for (std::uint64_t sample = 0; sample < 64; ++sample) {
      const RoomPath path = trace_from_centre(room, accel, kind, sample, kDepth);
      EXPECT_EQ(path.color, (Color{0, 0, 0})) << "no light in a closed room";
      if (path.rays == kDepth) {
        ++went_on;
      } else {
        ++ended;
        EXPECT_GE(path.rays, std::uint64_t(kRouletteFromDepth)) << "no path ends before it plays";
      }
      EXPECT_EQ(path.dimensions, bounce_dimension(int(path.rays))) << to_string(kind);
    }
  }
  EXPECT_GT(ended, 0);
  EXPECT_GT(went_on, 0);
}

// Without the roulette (--roulette off, the book's estimator) every path in the closed room
// runs to the depth limit, as the book's do.
TEST(RussianRoulette, OffEveryPathRunsToTheDepthLimit) {
  const Scene room = closed_room(Lambertian{{0.3f, 0.3f, 0.3f}});
  const NaiveAccel accel(room.spheres);
  constexpr int kDepth = 6;
  for (const SamplerKind kind :
       {SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::PaddedSobol}) {
    for (std::uint64_t sample = 0; sample < 64; ++sample) {
      const RoomPath path = trace_from_centre(room, accel, kind, sample, kDepth, false);
      EXPECT_EQ(path.rays, std::uint64_t(kDepth)) << to_string(kind) << " sample " << sample;
    }
  }
}

}  // namespace
}  // namespace rtiow
