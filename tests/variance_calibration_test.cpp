// The variance rtiow reports is the variance it delivers, for every sampler: two renders that
// differ only in their seed differ by what their variance channels say, pixel by pixel and
// over the image. (The sample variance over n, which the Sobol samplers used to report,
// gave 0.34 here: their error overstated about three times.) The renders are fixed, so the
// verdicts are too; the bands leave room for other seeds.

#include <gtest/gtest.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "core/compare/image_diff.h"
#include "core/film/replicate_variance.h"
#include "core/film/window_sums.h"
#include "core/render/render.h"
#include "core/render/render_statistics.h"
#include "core/scene/builtin_scenes.h"

namespace rtiow {
namespace {

// The mean over pixel-channels of (a - b)^2 / (var_a + var_b), and the same as a ratio of sums
// (the image-wide figure that --image-error and rtiow accuracy rest on): 1 when honest.
struct Calibration {
  double per_pixel = 0, image = 0;
  // What the figures come from, so seed pairs can be pooled: the sum and count of z^2 over the
  // pixel-channels with a variance, and the largest z^2.
  double z_squares = 0, counted = 0, largest = 0;
};

Calibration calibration(const RenderResult& a, const RenderResult& b) {
  const std::vector<Vec3d> va = pixel_mean_variances(a), vb = pixel_mean_variances(b);
  Calibration result;
  double squares = 0, variances = 0;
  for (std::size_t p = 0; p < va.size(); ++p) {
    for (std::size_t c = 0; c < 3; ++c) {
      const double d = double(a.film.pixels()[p][c]) - double(b.film.pixels()[p][c]);
      const double v = va[p][c] + vb[p][c];
      squares += d * d, variances += v;
      if (v > 0) {
        result.z_squares += d * d / v, result.counted += 1;
        result.largest = std::max(result.largest, d * d / v);
      }
    }
  }
  result.per_pixel = result.z_squares / result.counted;
  result.image = squares / variances;
  return result;
}

RenderSettings settings(const Scene& scene, int width, int spp, SamplerKind sampler) {
  RenderSettings s;
  s.width = width;
  s.height = int(std::lround(width / scene.image.aspect_ratio));
  s.samples = FixedSamples{spp};
  s.max_depth = 50;
  s.sampler = sampler;
  s.estimate_error = true;  // the variance channels' renders
  return s;
}

Calibration two_seeds(const Scene& scene, RenderSettings s) {
  s.seed = 1;
  const RenderResult a = render(scene, s);
  s.seed = 2;
  return calibration(a, render(scene, s));
}

// Measured at 160x107 (per pixel / image): independent 1.00 / 1.01, sobol 1.04 / 1.00,
// padded-sobol 1.01 / 1.02 at 64 spp; at 16 spp 1.05 / 1.00, 1.06 / 0.98, 1.07 / 0.98, where a
// pixel's own 15 degrees of freedom alone put the per-pixel mean near 1.04-1.07.
TEST(VarianceCalibration, TwoSeedsDifferByWhatTheVarianceChannelsSayForEverySampler) {
  const Scene cover = make_builtin_scene("cover", 1);
  for (const SamplerKind sampler :
       {SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::PaddedSobol}) {
    for (const int spp : {16, 64}) {
      const Calibration c = two_seeds(cover, settings(cover, 160, spp, sampler));
      const std::string where = to_string(sampler) + " at " + std::to_string(spp) + " spp";
      std::printf("%s: per pixel %.3f, image %.3f\n", where.c_str(), c.per_pixel, c.image);
      EXPECT_NEAR(c.per_pixel, 1.0, 0.15) << where;
      EXPECT_NEAR(c.image, 1.0, 0.1) << where;
    }
  }
}

// Beyond the cover: a glass, a diffuse and a metal sphere filling the frame (materials), and a
// lens (defocus). Measured (per pixel / image, 160 px wide, 64 spp): materials sobol 1.00 /
// 1.01, padded-sobol 1.02 / 1.01; defocus sobol 1.00 / 1.02, padded-sobol 1.01 / 1.04.
TEST(VarianceCalibration, HoldsOnTheOtherScenesForBothSobolSamplers) {
  for (const char* name : {"materials", "defocus"}) {
    const Scene scene = make_builtin_scene(name, 1);
    for (const SamplerKind sampler : {SamplerKind::Sobol, SamplerKind::PaddedSobol}) {
      const Calibration c = two_seeds(scene, settings(scene, 160, 64, sampler));
      const std::string where = std::string(name) + " " + to_string(sampler) + " at 64 spp";
      std::printf("%s: per pixel %.3f, image %.3f\n", where.c_str(), c.per_pixel, c.image);
      EXPECT_NEAR(c.per_pixel, 1.0, 0.15) << where;
      EXPECT_NEAR(c.image, 1.0, 0.1) << where;
    }
  }
}

// At 1024 spp the sampler's gain differs between channels: on the blue diffuse sphere of
// `materials` red and green converge faster than blue. With one ratio for all three channels
// the per-pixel figure was 1.23 (red and green understated 2.5x on the sphere); per channel,
// trimmed, with an own-replicate weight of 1/8: 1.08 (padded-sobol 1.26 -> 1.06,
// docs/accuracy.md). The band is 1 +- 0.1.
TEST(VarianceCalibration, HoldsAt1024SppWhereTheChannelsConvergeDifferently) {
  const Scene scene = make_builtin_scene("materials", 1);
  const Calibration c = two_seeds(scene, settings(scene, 160, 1024, SamplerKind::Sobol));
  std::printf("materials sobol at 1024 spp: per pixel %.3f, image %.3f\n", c.per_pixel, c.image);
  EXPECT_NEAR(c.per_pixel, 1.0, 0.1);
  EXPECT_NEAR(c.image, 1.0, 0.1);
}

TEST(VarianceCalibration, AdaptiveRendersReportTheirVarianceHonestly) {
  const Scene cover = make_builtin_scene("cover", 1);
  RenderSettings s = settings(cover, 160, 64, SamplerKind::Sobol);
  s.samples = AdaptiveBudget{64};
  const Calibration c = two_seeds(cover, s);
  std::printf("sobol --adaptive 64: per pixel %.3f, image %.3f\n", c.per_pixel, c.image);
  EXPECT_NEAR(c.per_pixel, 1.0, 0.15);
  EXPECT_NEAR(c.image, 1.0, 0.1);
}

// Scenes made for the estimator's weak spots (issue 42). A ground of albedo 0.4 lit by the sky:
// its blue is 0.4 on every one-bounce path (the sky's blue is 1 everywhere), so blue is
// constant within most pixels, and the few with a second bounce stand among neighbours with
// no spread at all. Its red and green vary smoothly with the bounce, except on the rare paths
// that reach a sphere.
Scene sky_lit_ground() {
  Scene s;
  const auto ground = s.add_material(Lambertian{{0.4f, 0.4f, 0.4f}});
  s.spheres.add({0.0f, -1000.0f, 0.0f}, 1000.0f, ground);
  s.spheres.add({-0.6f, 0.25f, -1.0f}, 0.25f, s.add_material(Lambertian{{0.7f, 0.3f, 0.3f}}));
  s.spheres.add({0.6f, 0.2f, -0.5f}, 0.2f, s.add_material(make_metal({0.8f, 0.8f, 0.8f}, 0.3f)));
  s.camera.lookfrom = {0, 1, 2};
  s.camera.lookat = {0, 0, -1};
  s.camera.vfov_degrees = 60.0;
  s.image = ImageSettings{72, 1.5, 8, 50};
  return s;
}

// A glass ball in front of a rough metal one through a wide lens, on the same ground.
Scene glass_over_rough_metal() {
  Scene s;
  const auto glass = s.add_material(Dielectric{1.5f});
  const auto rough = s.add_material(make_metal({0.7f, 0.6f, 0.5f}, 0.8f));
  s.spheres.add({0.0f, -1000.0f, 0.0f}, 1000.0f, s.add_material(Lambertian{{0.4f, 0.4f, 0.4f}}));
  s.spheres.add({0.0f, 0.5f, -1.5f}, 0.5f, rough);
  s.spheres.add({0.0f, 0.35f, 0.0f}, 0.35f, glass);
  s.spheres.add({-1.2f, 0.3f, -3.0f}, 0.3f, rough);
  s.camera.lookfrom = {0, 0.5, 2.5};
  s.camera.lookat = {0, 0.4, -1};
  s.camera.vfov_degrees = 40.0;
  s.camera.aperture = 0.15;
  s.camera.focus_distance = 2.0;
  s.image = ImageSettings{72, 1.5, 8, 50};
  return s;
}

// Over seed pairs: the mean of z^2 over every pixel-channel with a variance, and the largest.
struct PairsCalibration {
  double mean = 0, largest = 0;
};

PairsCalibration over_seed_pairs(const Scene& scene, RenderSettings s, int pairs) {
  double total = 0, count = 0, largest = 0;
  for (int pair = 0; pair < pairs; ++pair) {
    s.seed = std::uint64_t(2 * pair + 1);
    const RenderResult a = render(scene, s);
    s.seed = std::uint64_t(2 * pair + 2);
    const Calibration c = calibration(a, render(scene, s));
    total += c.z_squares, count += c.counted, largest = std::max(largest, c.largest);
  }
  return {total / count, largest};
}

// Where a channel is constant within most pixels, a noisy pixel used to take its ratio from
// neighbours with no spread but rounding (ratio 0) and, its own replicates agreeing, reported a
// variance of 0: z^2 up to 1e10 in 7 of 12 seed pairs at 8 spp. Now no pixel-channel passes
// z^2 = 1000, and the mean is that of independent samples: with 7 degrees of freedom per
// pixel and render, Jensen alone puts a Gaussian pixel's E[z^2] at 14/12 = 1.17 (8 spp), 30/28
// = 1.07 (16), 62/60 = 1.03 (32); the independent sampler measures 1.16, 1.06, 1.03 here.
// Measured over 20 pairs at 96 px (sobol / padded-sobol): ground 1.06 / 1.06 at 8 spp, 1.00 /
// 1.01 at 16, 0.97 / 0.97 at 32, largest 330; glass over metal 1.06 / 1.05, 0.99 / 1.00, 1.00 /
// 1.00 (was: up to 7e4 in the mean). The bands are the issue's: 1 +- 0.15 at 8, 1 +- 0.1 above.
TEST(VarianceCalibration, NoPixelClaimsZeroVarianceWhereItsChannelIsConstantAround) {
  for (const Scene& scene : {sky_lit_ground(), glass_over_rough_metal()}) {
    for (const SamplerKind sampler : {SamplerKind::Sobol, SamplerKind::PaddedSobol}) {
      for (const int spp : {8, 16, 32}) {
        const PairsCalibration c = over_seed_pairs(scene, settings(scene, 72, spp, sampler), 20);
        const std::string where = to_string(sampler) + " at " + std::to_string(spp) + " spp";
        std::printf("%s: mean z^2 %.3f, largest %.3g\n", where.c_str(), c.mean, c.largest);
        EXPECT_LT(c.largest, 1000.0) << where;
        EXPECT_NEAR(c.mean, 1.0, spp == 8 ? 0.15 : 0.1) << where;
      }
    }
  }
}

// A render keeps the replicate ratios its error estimate was made with, so that the variance
// channels do not work them out again (a third of a second a megapixel); the variances from
// them are the bits worked out afresh, and a result without them (a merge's) still has them.
TEST(VarianceCalibration, TheVarianceChannelsTakeTheRatiosTheEstimateKept) {
  const Scene scene = sky_lit_ground();
  RenderResult r = render(scene, settings(scene, 72, 16, SamplerKind::Sobol));
  ASSERT_TRUE(r.replicate_ratios);
  EXPECT_EQ(r.replicate_ratios->size(), r.pixel_samples.size());
  const std::vector<Vec3d> kept = pixel_mean_variances(r);
  r.replicate_ratios.reset();
  const std::vector<Vec3d> afresh = pixel_mean_variances(r);
  ASSERT_EQ(kept.size(), afresh.size());
  for (std::size_t p = 0; p < kept.size(); ++p) {
    for (std::size_t c = 0; c < 3; ++c)
      EXPECT_EQ(std::bit_cast<std::uint64_t>(kept[p][c]),
                std::bit_cast<std::uint64_t>(afresh[p][c]))
          << "pixel " << p << " channel " << c;
  }
}

// What rtiow diff reads from an --stats-channels EXR: the film and its variance channels.
DiffInput with_variances(const RenderResult& r) {
  DiffInput d = diff_input(r.film);
  for (const Vec3d& v : pixel_mean_variances(r)) {
    for (std::size_t c = 0; c < 3; ++c) d.variance.push_back(float(v[c]));
  }
  return d;
}

// rtiow diff's noise mode on default (sobol) renders: noise alone fails at most alpha of seed
// pairs, the mean and the blocks together. At alpha = 0.2, 40 pairs fail 8 on average at the
// most; more than 13 has a chance of 3% at 0.2 (testing the mean and each block at alpha, as
// diff once did, failed about 2 alpha). Measured through the command at 160x90, 64 spp, over
// 100 pairs: see docs/diff.md.
TEST(VarianceCalibration, NoiseDiffOfSeedPairsFailsAtMostAlphaOfThem) {
  const Scene cover = make_builtin_scene("cover", 1);
  RenderSettings s = settings(cover, 96, 32, SamplerKind::Sobol);
  int failures = 0;
  for (std::uint64_t pair = 0; pair < 40; ++pair) {
    s.seed = 2 * pair + 11;
    const DiffInput a = with_variances(render(cover, s));
    s.seed = 2 * pair + 12;
    const DiffInput b = with_variances(render(cover, s));
    failures += noise_diff(b, a, 16, 0.2).verdict == DiffVerdict::Fail;
  }
  std::printf("noise diff at alpha 0.2: %d of 40 seed pairs fail\n", failures);
  EXPECT_LE(failures, 13);
}

TEST(ReplicateVariance, CountsTheOddSamplesOfAnyRange) {
  EXPECT_EQ(odd_samples(0, 0), 0u);
  EXPECT_EQ(odd_samples(0, 1), 0u);
  EXPECT_EQ(odd_samples(0, 2), 1u);
  EXPECT_EQ(odd_samples(0, 3), 1u);
  EXPECT_EQ(odd_samples(1, 1), 1u);
  EXPECT_EQ(odd_samples(1, 3), 2u);
  EXPECT_EQ(odd_samples(7, 10), 5u);
}

TEST(ReplicateVariance, IsTheSquaredDifferenceOfTheReplicatesMeansWeightedByTheirCounts) {
  PixelSum sum;
  PixelSpread spread;
  // Samples 0..3: 1, 3, 1, 3 (even ones 1, odd ones 3): replicate means 1 and 3.
  for (std::uint64_t i = 0; i < 4; ++i) {
    const Color c = i % 2 ? Color{3, 3, 3} : Color{1, 1, 1};
    sum.add(c);
    spread.add(c, i);
  }
  EXPECT_DOUBLE_EQ(replicate_estimate(sum, spread, 0, 4).x, 4.0 / 4.0);
  // One replicate empty: no estimate.
  PixelSum one;
  PixelSpread one_spread;
  one.add({2, 2, 2});
  one_spread.add({2, 2, 2}, 0);
  EXPECT_EQ(replicate_estimate(one, one_spread, 0, 1).x, 0.0);
}

// Where every pixel's replicates agree exactly (no spread between them) but its samples do
// vary, and each pixel has more than kReplicateMinNeighbours such neighbours, the honest
// variance is 0, not the sample variance: the replicates rule.
TEST(ReplicateVariance, ScalesTheSampleVarianceByTheNeighboursReplicates) {
  constexpr int w = 12, h = 12;  // every pixel's window holds at least 63 others
  std::vector<PixelSum> sums(w * h);
  std::vector<PixelSpread> spreads(w * h);
  std::vector<std::uint32_t> samples(w * h, 4);
  for (std::size_t p = 0; p < sums.size(); ++p) {
    for (std::uint64_t i = 0; i < 4; ++i) {
      const Color c = i < 2 ? Color{1, 1, 1} : Color{3, 3, 3};  // replicates: {1, 3} and {1, 3}
      sums[p].add(c);
      spreads[p].add(c, i);
    }
  }
  for (const Vec3d& v : honest_variances(w, h, sums, spreads, samples, 0, SamplerKind::Sobol))
    EXPECT_EQ(v.x, 0.0);
  // Replicates {1, 1} and {3, 3}: their spread is all of the sample variance's and more.
  for (std::size_t p = 0; p < sums.size(); ++p) {
    sums[p] = PixelSum{}, spreads[p] = PixelSpread{};
    for (std::uint64_t i = 0; i < 4; ++i) {
      const Color c = i % 2 ? Color{3, 3, 3} : Color{1, 1, 1};
      sums[p].add(c);
      spreads[p].add(c, i);
    }
  }
  // Sample variance over n: (4 * 1) / 3 / 4 = 1/3; replicate estimate 1: the ratio is 3.
  for (const Vec3d& v : honest_variances(w, h, sums, spreads, samples, 0, SamplerKind::Sobol)) {
    EXPECT_NEAR(v.x, 1.0, 1e-9);
  }
}

// The trimmed windows are walked four pixels at a time where they lie whole inside the image
// and one at a time elsewhere: a window gives the same ratio, bit for bit, whichever way it is
// walked. A column without samples put before the image shifts which pixels share a walk
// (and which take the one-at-a-time path at the right edge) but not any window of a pixel
// seven or more columns in.
TEST(ReplicateVariance, AWindowGivesTheSameRatioHoweverItIsWalked) {
  constexpr int w = 41, h = 19, r = kReplicateWindowRadius;
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(0.0f, 1.0f);
  std::vector<PixelSum> sums(w * h), shifted_sums((w + 1) * h);
  std::vector<PixelSpread> spreads(w * h), shifted_spreads((w + 1) * h);
  std::vector<std::uint32_t> samples(w * h, 8), shifted_samples((w + 1) * h, 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t p = std::size_t(y * w + x), q = std::size_t(y * (w + 1) + x + 1);
      const float scale = x % 5 == 0 ? 8.0f : 1.0f;  // some noisier pixels for the trim
      for (std::uint64_t i = 0; i < 8; ++i)
        add_sample(sums[p], spreads[p],
                   Color{scale * value(random), value(random), value(random) * value(random)}, i);
      shifted_sums[q] = sums[p], shifted_spreads[q] = spreads[p], shifted_samples[q] = 8;
    }
  }
  const std::vector<Vec3d> ratios =
      replicate_ratios(w, h, sums, spreads, samples, 0, SamplerKind::Sobol);
  const std::vector<Vec3d> shifted = replicate_ratios(w + 1, h, shifted_sums, shifted_spreads,
                                                      shifted_samples, 0, SamplerKind::Sobol);
  int compared = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = r; x < w; ++x) {
      const Vec3d a = ratios[std::size_t(y * w + x)], b = shifted[std::size_t(y * (w + 1) + x + 1)];
      for (std::size_t c = 0; c < 3; ++c) {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(a[c]), std::bit_cast<std::uint64_t>(b[c]))
            << "pixel " << x << "," << y << " channel " << c;
      }
      compared += a.x != 1.0;  // a trimmed ratio, not the fallback's 1
    }
  }
  EXPECT_GT(compared, (w - r) * h / 2);
}

// The window sums are summed-area tables built in parallel: each window's sum is its pixels' sum
// (to rounding), and the ratios made of them, an adaptive render's classes of counts included,
// are the same bits on any number of threads.
TEST(ReplicateVariance, TheWindowsAndTheRatiosAreTheSameBitsOnAnyNumberOfThreads) {
  constexpr int w = 70, h = 45, r = 3;
  std::mt19937 random(11);
  std::uniform_real_distribution<float> value(0.0f, 1.0f);
  std::vector<double> values(w * h);
  for (double& v : values) v = value(random);
  const std::vector<double> sums = window_sums(values, w, h, r);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double direct = 0;
      for (int ny = std::max(0, y - r); ny <= std::min(h - 1, y + r); ++ny)
        for (int nx = std::max(0, x - r); nx <= std::min(w - 1, x + r); ++nx)
          direct += values[std::size_t(ny * w + nx)];
      EXPECT_NEAR(sums[std::size_t(y * w + x)], direct, 1e-12) << x << "," << y;
    }
  }
  std::vector<PixelSum> pixel_sums(w * h);
  std::vector<PixelSpread> spreads(w * h);
  std::vector<std::uint32_t> samples(w * h);
  for (std::size_t p = 0; p < pixel_sums.size(); ++p) {
    samples[p] = 4u << (p % 5);  // five classes of counts, as an adaptive render's
    for (std::uint64_t i = 0; i < samples[p]; ++i)
      add_sample(pixel_sums[p], spreads[p], Color{value(random), value(random), value(random)}, i);
  }
  const auto ratios_on = [&](int threads) {
    return tbb::task_arena(threads).execute([&] {
      return replicate_ratios(w, h, pixel_sums, spreads, samples, 0, SamplerKind::Sobol);
    });
  };
  const std::vector<Vec3d> one = ratios_on(1), three = ratios_on(3);
  ASSERT_EQ(one.size(), three.size());
  int borrowed = 0;  // ratios taken from the pixel's own class, not the fallback's 1
  for (std::size_t p = 0; p < one.size(); ++p) {
    for (std::size_t c = 0; c < 3; ++c)
      EXPECT_EQ(std::bit_cast<std::uint64_t>(one[p][c]), std::bit_cast<std::uint64_t>(three[p][c]));
    borrowed += one[p].x != 1.0;
  }
  EXPECT_GT(borrowed, w * h / 2);
}

// Samples of one pixel: `values[i]` is sample i's value in every channel.
void fill(PixelSum& sum, PixelSpread& spread, const std::vector<float>& values) {
  sum = PixelSum{}, spread = PixelSpread{};
  for (std::size_t i = 0; i < values.size(); ++i) {
    add_sample(sum, spread, Color{values[i], values[i], values[i]}, i);
  }
}

// The issue-42 pixel: its eight samples are six 0.4s and two 0.16s, one 0.16 in each replicate
// (replicate estimate 0), among neighbours whose samples are all 0.4 (no spread but rounding).
// Those neighbours say nothing about the sampler's gain, so the pixel keeps 7/8 of its sample
// variance (the independent bound); it reported 0.
TEST(ReplicateVariance, ANoisyPixelAmongConstantOnesKeepsItsSampleVariance) {
  constexpr int w = 20, h = 20;
  std::vector<PixelSum> sums(w * h);
  std::vector<PixelSpread> spreads(w * h);
  const std::vector<std::uint32_t> samples(w * h, 8);
  const std::vector<float> constant(8, 0.4f);
  for (std::size_t p = 0; p < sums.size(); ++p) fill(sums[p], spreads[p], constant);
  const std::size_t noisy = 10 * w + 10, other = 3 * w + 15;
  fill(sums[noisy], spreads[noisy], {0.4f, 0.4f, 0.16f, 0.4f, 0.4f, 0.16f, 0.4f, 0.4f});
  fill(sums[other], spreads[other], {0.16f, 0.4f, 0.4f, 0.4f, 0.4f, 0.4f, 0.4f, 0.16f});
  ASSERT_EQ(replicate_estimate(sums[noisy], spreads[noisy], 0, 8).x, 0.0);
  const std::vector<Vec3d> v =
      honest_variances(w, h, sums, spreads, samples, 0, SamplerKind::Sobol);
  const double sample_variance = variance_of_mean(sums[noisy], spreads[noisy], 8).x;
  EXPECT_GT(sample_variance, 1e-3);
  EXPECT_NEAR(v[noisy].x, (1.0 - kOwnReplicateWeight) * sample_variance, 1e-9);
  EXPECT_GT(v[other].x, 0.0);
  // The constant pixels have no spread, and report none.
  EXPECT_EQ(v[0].x, 0.0);
  EXPECT_EQ(variance_of_mean(sums[0], spreads[0], 8).x, 0.0);
}

// Samples equal to the sums' resolution (floats a few ulps apart) have no spread; samples
// 1e-4 apart do.
TEST(ReplicateVariance, SamplesEqualToTheSumsResolutionHaveNoSpread) {
  PixelSum sum;
  PixelSpread spread;
  fill(sum, spread, {1.0f, std::nextafter(1.0f, 2.0f), 1.0f, std::nextafter(1.0f, 0.0f)});
  EXPECT_EQ(variance_of_mean(sum, spread, 4).x, 0.0);
  fill(sum, spread, {1000.0f, 1000.0f, 1000.0f, 1000.0f, 1000.0f});
  EXPECT_EQ(variance_of_mean(sum, spread, 5).x, 0.0);
  fill(sum, spread, {1.0f, 1.0001f, 1.0f, 1.0001f});
  EXPECT_NEAR(variance_of_mean(sum, spread, 4).x, 1e-8 / 3.0 / 4.0 * 1.0, 2e-10);
}

// A quiet region beside a noisy one: a quiet pixel whose window reaches the noisy pixels takes
// its ratio from the quiet ones (kReplicateTrimFactor), not from a ratio of sums the noisy ones
// dominate. Quiet pixels' replicates agree exactly (ratio 0); noisy ones' ratio is 3.
TEST(ReplicateVariance, AQuietPixelTakesItsRatioFromItsQuietNeighbours) {
  constexpr int w = 20, h = 20;
  std::vector<PixelSum> sums(w * h);
  std::vector<PixelSpread> spreads(w * h);
  const std::vector<std::uint32_t> samples(w * h, 4);
  for (std::size_t p = 0; p < sums.size(); ++p) {
    const bool noisy = p % w >= 10;
    for (std::uint64_t i = 0; i < 4; ++i) {
      // Quiet: replicates {1, 1.001} and {1, 1.001}. Noisy: {1, 1} and {3, 3}.
      const float quiet = i < 2 ? 1.0f : 1.001f, loud = i % 2 ? 3.0f : 1.0f;
      const Color c = noisy ? Color{loud, loud, loud} : Color{quiet, quiet, quiet};
      sums[p].add(c);
      spreads[p].add(c, i);
    }
  }
  const std::vector<Vec3d> v =
      honest_variances(w, h, sums, spreads, samples, 0, SamplerKind::Sobol);
  for (int y = 0; y < h; ++y) {
    // Column 8: its 3x3 neighbours are quiet, its 15x15 window reaches the noisy columns 10-15.
    EXPECT_EQ(v[std::size_t(y * w + 8)].x, 0.0) << "row " << y;
    // Column 12 is noisy: its ratio stays its region's, 3 (the quiet neighbours it keeps add
    // next to nothing to the window's sums).
    EXPECT_NEAR(v[std::size_t(y * w + 12)].x, 1.0, 1e-3) << "row " << y;
  }
}

}  // namespace
}  // namespace rtiow
