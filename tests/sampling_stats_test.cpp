// The samplers and adaptive sampling against a high-spp reference: unbiased (the image sum
// agrees with the reference's within its standard error), the error each promises, and
// the convergence rate of independent sampling. The renders are deterministic, so these
// verdicts are too; the thresholds leave room for other seeds.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/film/image_error.h"
#include "core/film/pixel_variance.h"
#include "core/render/render.h"
#include "core/render/render_statistics.h"
#include "core/scene/builtin_scenes.h"

namespace rtiow {
namespace {

constexpr int kWidth = 48;
constexpr double kMaxZ = 4.0;  // |difference| / standard error beyond this is a bias
// --adaptive measured 1.02-1.26x lower relMSE per ray than uniform at 48x32 and 128 spp (seeds
// 1-3, both samplers; means over the seeds 1.24 independent, 1.11 sobol); the per-pixel rule of
// --target-error measured 0.86-1.03x at equal time.
constexpr double kMinBudgetGain = 1.05;

RenderSettings settings(const Scene& scene, int spp, std::uint64_t seed) {
  RenderSettings s;
  s.width = kWidth;
  s.height = int(std::lround(kWidth / scene.image.aspect_ratio));
  s.samples = FixedSamples{spp};
  s.max_depth = 50;
  s.seed = seed;
  s.sampler = SamplerKind::Independent;
  s.estimate_error = true;  // every render here is measured with its own standard error
  return s;
}

const Scene& cover() {
  static const Scene scene = make_builtin_scene("cover", 1);
  return scene;
}

const ImageEstimate& reference() {
  static const ImageEstimate image = to_estimate(render(cover(), settings(cover(), 4096, 999)));
  return image;
}

ImageError error_of(const RenderSettings& s) {
  return measure_error(to_estimate(render(cover(), s)), reference());
}

// The standard error of the image mean's difference is calibrated: over seeds, the z-scores of
// unbiased renders have an RMS near 1 (1.14-1.18 measured over 40 seeds; 1.9-2.0 while a pixel's
// three channels were summed as if independent).
TEST(ImageError, TheImageMeansStandardErrorIsCalibratedOverSeeds) {
  constexpr int kSeeds = 30;
  double squares = 0;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const ImageError e = error_of(settings(cover(), 16, 100 + seed));
    const double z = e.mean_difference / e.mean_difference_error;
    squares += z * z / kSeeds;
  }
  std::printf("RMS z over %d seeds: %.2f\n", kSeeds, std::sqrt(squares));
  EXPECT_GT(std::sqrt(squares), 0.7) << "the standard error is too large";
  EXPECT_LT(std::sqrt(squares), 1.45) << "the standard error is too small";
}

TEST(AdaptiveSampling, AgreesInTheMeanWithTheReferenceAndReachesItsTarget) {
  for (const double target : {0.2, 0.1}) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      RenderSettings s = settings(cover(), 1024, seed);
      s.samples = PixelErrorTarget{target, 1024};
      const ImageError e = error_of(s);
      EXPECT_LT(std::abs(e.mean_difference), kMaxZ * e.mean_difference_error)
          << "target " << target << " seed " << seed << ": " << e.mean_difference << " +- "
          << e.mean_difference_error;
      EXPECT_LT(std::sqrt(e.rel_mse), 1.1 * target) << "target " << target << " seed " << seed;
    }
  }
}

TEST(AdaptiveSampling, SpendsSamplesWhereTheNoiseIs) {
  RenderSettings s = settings(cover(), 1024, 4);
  s.samples = PixelErrorTarget{0.1, 1024};
  const RenderResult r = render(cover(), s);
  // The sky (top row) is smooth and stops at the minimum; the image as a whole needs more
  // (29.5 on average, and some pixels several times the minimum).
  for (int x = 0; x < s.width; ++x) EXPECT_EQ(r.pixel_samples[std::size_t(x)], 16u) << x;
  EXPECT_GT(mean_samples(r), 24.0);
  EXPECT_GT(*std::max_element(r.pixel_samples.begin(), r.pixel_samples.end()), 64u);
}

// The book's estimator (--roulette off: every path to its depth) and the renderer's (the
// reference's, with the roulette) have one expected image: the mean agrees within its error.
// Off, the paths that carried almost nothing go on, so it traces more rays (6-7% on the cover).
TEST(RussianRoulette, OffAgreesInTheMeanAndTracesMoreRays) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    RenderSettings s = settings(cover(), 256, seed);
    const RenderResult on = render(cover(), s);
    s.russian_roulette = false;
    const RenderResult off = render(cover(), s);
    const ImageError e = measure_error(to_estimate(off), reference());
    EXPECT_LT(std::abs(e.mean_difference), kMaxZ * e.mean_difference_error)
        << "seed " << seed << ": " << e.mean_difference << " +- " << e.mean_difference_error;
    EXPECT_GT(off.rays_traced, on.rays_traced) << "seed " << seed;
  }
}

// Measured 2.8x (sobol) and 2.1x (padded-sobol) at 160x107 and spp >= 16 (rtiow accuracy);
// the margin is for other seeds and this smaller image.
TEST(SobolSamplers, AgreeInTheMeanAndBeatIndependentSamplingAtEqualSpp) {
  for (const SamplerKind sampler : {SamplerKind::Sobol, SamplerKind::PaddedSobol}) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      RenderSettings s = settings(cover(), 64, seed);
      const ImageError independent = error_of(s);
      s.sampler = sampler;
      const ImageError sobol = error_of(s);
      const std::string where = to_string(sampler) + " seed " + std::to_string(seed);
      EXPECT_LT(std::abs(sobol.mean_difference), kMaxZ * sobol.mean_difference_error) << where;
      EXPECT_GT(independent.rel_mse / sobol.rel_mse, 1.5) << where;
    }
  }
}

// A render that estimates nothing draws one sequence of n points, not two replicates of n/2:
// as unbiased, and no noisier (docs/accuracy.md measures the gain at 400x225 over seed pairs; on
// this small image and three seeds the ratio is noisy: sobol 0.93, padded-sobol 1.02, so the
// bound only catches a sampler made noisier). Its mean is judged with the replicates' standard
// error, which is larger than its own.
TEST(SobolSamplers, OneSequenceAgreesInTheMeanAndIsLessNoisyThanReplicates) {
  for (const SamplerKind sampler : {SamplerKind::Sobol, SamplerKind::PaddedSobol}) {
    double one_sum = 0, two_sum = 0;
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      RenderSettings s = settings(cover(), 64, seed);
      s.sampler = sampler;
      const ImageEstimate two = to_estimate(render(cover(), s));
      s.estimate_error = false;
      const RenderResult one = render(cover(), s);
      EXPECT_EQ(one.replicates, 1);
      const ImageError e1 = measure_error({one.film, two.variance}, reference());
      const ImageError e2 = measure_error(two, reference());
      const std::string where = to_string(sampler) + " seed " + std::to_string(seed);
      EXPECT_LT(std::abs(e1.mean_difference), kMaxZ * e1.mean_difference_error) << where;
      one_sum += e1.rel_mse, two_sum += e2.rel_mse;
    }
    std::printf("%s: relMSE one sequence / two replicates = %.3f\n", to_string(sampler).c_str(),
                one_sum / two_sum);
    EXPECT_LT(one_sum, 1.15 * two_sum) << to_string(sampler);
  }
}

// --adaptive spends the cost of N uniform samples where it lowers the image's relMSE most. Its
// pixels' means stay unbiased, and per ray it beats uniform sampling with the same sampler
// (the rays are counted, not timed: deterministic).
TEST(AdaptiveOnABudget, AgreesInTheMeanAndBeatsUniformSamplingPerRay) {
  for (const SamplerKind sampler : {SamplerKind::Independent, SamplerKind::Sobol}) {
    double gains = 0;
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      RenderSettings s = settings(cover(), 128, seed);
      s.sampler = sampler;
      const RenderResult uniform = render(cover(), s);
      s.samples = AdaptiveBudget{128};
      const RenderResult adaptive = render(cover(), s);
      const ImageError u = measure_error(to_estimate(uniform), reference()),
                       a = measure_error(to_estimate(adaptive), reference());
      const std::string where = to_string(sampler) + " seed " + std::to_string(seed);
      EXPECT_LT(std::abs(a.mean_difference), kMaxZ * a.mean_difference_error) << where;
      EXPECT_NEAR(double(adaptive.rays_traced) / double(uniform.rays_traced), 1.0, 0.05)
          << where << ": the budget is the uniform render's cost";
      const double gain =
          (u.rel_mse * double(uniform.rays_traced)) / (a.rel_mse * double(adaptive.rays_traced));
      std::printf("%s: relMSE per ray %.2fx lower than uniform\n", where.c_str(), gain);
      EXPECT_GT(gain, 0.95) << where << ": worse than uniform";
      gains += gain / 3.0;
    }
    EXPECT_GT(gains, kMinBudgetGain) << to_string(sampler) << ", the mean over three seeds";
  }
}

// Where no error is asked, --adaptive draws one sequence, not two replicates: its budget only
// weighs pixels against one another, for which one sequence's sample variance serves. It stays
// unbiased (a pixel's count comes from its neighbours' samples, never its own; its mean is
// judged with the replicates' standard error, as a one-sequence render reports none), and per
// ray it beats a uniform render that also draws one sequence (measured at 48x32, 128 spp:
// 1.11-1.29x, mean 1.17).
TEST(AdaptiveOnABudget, DrawsOneSequenceWhereNoErrorIsAskedAndBeatsUniformSamplingPerRay) {
  double gains = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    RenderSettings s = settings(cover(), 128, seed);
    s.sampler = SamplerKind::Sobol;
    s.samples = AdaptiveBudget{128};
    const ImageEstimate replicates = to_estimate(render(cover(), s));
    s.estimate_error = false;
    const RenderResult adaptive = render(cover(), s);
    s.samples = FixedSamples{128};
    const RenderResult uniform = render(cover(), s);
    const std::string where = "seed " + std::to_string(seed);
    EXPECT_EQ(adaptive.replicates, 1) << where;
    const ImageError a = measure_error({adaptive.film, replicates.variance}, reference()),
                     u = measure_error({uniform.film, replicates.variance}, reference());
    EXPECT_LT(std::abs(a.mean_difference), kMaxZ * a.mean_difference_error) << where;
    const double gain =
        (u.rel_mse * double(uniform.rays_traced)) / (a.rel_mse * double(adaptive.rays_traced));
    std::printf("%s: one sequence, relMSE per ray %.2fx lower than uniform\n", where.c_str(), gain);
    EXPECT_GT(gain, 0.95) << where << ": worse than uniform";
    gains += gain / 3.0;
  }
  EXPECT_GT(gains, kMinBudgetGain) << "the mean over three seeds";
  // An error target keeps its two replicates: its stopping rule needs a calibrated error.
  RenderSettings target = settings(cover(), 64, 1);
  target.sampler = SamplerKind::Sobol;
  target.estimate_error = false;
  target.samples = ImageErrorTarget{0.2, 64};
  EXPECT_EQ(replicates(target), kReplicates);
  target.samples = PixelErrorTarget{0.2, 64};
  EXPECT_EQ(replicates(target), kReplicates);
}

// The error asked for is the error delivered: with honest variances (core/film/
// replicate_variance.h) the render stops where its true relative RMS error reaches the target,
// and never above it (it aims at 0.92 of it; it stopped at 0.54-0.70 of it while the sample
// variance stood for the Sobol mean's).
// The bias check takes the sample variance's standard error, an upper bound for a Sobol
// render's.
TEST(ImageError, AgreesInTheMeanAndDeliversTheErrorAskedFor) {
  for (const double target : {0.1, 0.05}) {
    // A bias is the same in every seed: the seeds' mean difference against its standard error.
    double difference = 0, error_squared = 0;
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      RenderSettings s = settings(cover(), 4096, seed);
      s.sampler = SamplerKind::Sobol;
      s.samples = ImageErrorTarget{target, 4096};
      const RenderResult r = render(cover(), s);
      ImageEstimate bounded = to_estimate(r);
      for (std::size_t p = 0; p < bounded.variance.size(); ++p) {
        bounded.variance[p] =
            variance_of_mean(r.sums.color[p], r.sums.spreads[p], r.pixel_samples[p]);
      }
      const ImageError e = measure_error(bounded, reference());
      const double delivered = std::sqrt(measure_error(to_estimate(r), reference()).rel_mse);
      std::printf("target %.2f seed %llu: delivered %.3f of it, image mean z %.2f\n", target,
                  static_cast<unsigned long long>(seed), delivered / target,
                  e.mean_difference / e.mean_difference_error);
      difference += e.mean_difference / 3.0;
      error_squared += e.mean_difference_error * e.mean_difference_error / 9.0;
      EXPECT_LT(delivered, 1.0 * target) << "target " << target << " seed " << seed;
      EXPECT_GT(delivered, 0.8 * target) << "not wastefully below it";
    }
    EXPECT_LT(std::abs(difference), kMaxZ * std::sqrt(error_squared)) << "target " << target;
  }
}

// Every render reports its image error (the relative RMS error, offset 0.01), fixed counts
// included, and the number is what it claims against an independent reference: a render with
// two replicates (or independent samples) calls its estimate calibrated and it is, within
// [0.8, 1.25] of the true error in the mean over seeds (measured 0.99-1.06 here); a render of
// one Sobol sequence calls its estimate an upper bound and it is one, in every seed (measured
// 1.32-1.63x in the mean at 16-64 spp). The reference, its own noise taken out, is a 4096-spp
// render.
TEST(ImageError, EveryRendersEstimateIsCalibratedOrABoundAsItSays) {
  struct Case {
    SamplerKind sampler;
    bool replicates;
    ErrorEstimate claimed;
  };
  const Case cases[] = {{SamplerKind::Independent, true, ErrorEstimate::Calibrated},
                        {SamplerKind::Sobol, true, ErrorEstimate::Calibrated},
                        {SamplerKind::PaddedSobol, true, ErrorEstimate::Calibrated},
                        {SamplerKind::Sobol, false, ErrorEstimate::UpperBound},
                        {SamplerKind::PaddedSobol, false, ErrorEstimate::UpperBound}};
  constexpr int kSeeds = 4;
  for (const Case& c : cases) {
    for (const int spp : {16, 64}) {
      double ratios = 0;
      for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
        RenderSettings s = settings(cover(), spp, seed);
        s.sampler = c.sampler;
        s.estimate_error = c.replicates;
        const RenderResult r = render(cover(), s);
        const std::string where = to_string(c.sampler) + (c.replicates ? ", replicates" : "") +
                                  ", " + std::to_string(spp) + " spp, seed " + std::to_string(seed);
        ASSERT_EQ(r.error_estimate, c.claimed) << where;
        const double truth = std::sqrt(measure_error({r.film, {}}, reference()).rel_mse);
        const double ratio = r.estimated_image_error / truth;
        if (c.claimed == ErrorEstimate::UpperBound) {
          EXPECT_GT(ratio, 1.0) << where << ": not a bound";
        }
        ratios += ratio / kSeeds;
      }
      std::printf("%s%s, %d spp: estimated over true image error %.3f (mean of %d seeds)\n",
                  to_string(c.sampler).c_str(), c.replicates ? ", replicates" : "", spp, ratios,
                  kSeeds);
      if (c.claimed == ErrorEstimate::Calibrated) {
        EXPECT_GT(ratios, 0.8) << to_string(c.sampler) << " " << spp;
        EXPECT_LT(ratios, 1.25) << to_string(c.sampler) << " " << spp;
      }
    }
  }
  // One sample has no spread: no estimate, and none is claimed.
  RenderSettings one = settings(cover(), 1, 1);
  EXPECT_EQ(render(cover(), one).error_estimate, ErrorEstimate::None);
}

// --target-error E: each pixel whose count the target decided (above the minimum, below the
// cap) ends with its true relative error, the RMS over eight seeds against the reference, at
// 0.85-1.0 E at the median (measured 0.88-0.90 on the cover at 160x107 and 0.89-0.92 here;
// 0.80-0.84 while the neighbours' mean judged a pixel, docs/accuracy.md).
TEST(TargetError, TheMedianPixelStopsAtTheErrorAskedFor) {
  constexpr int kSeeds = 8;
  const std::vector<Color>& ref = reference().film.pixels();
  for (const SamplerKind sampler : {SamplerKind::Sobol, SamplerKind::Independent}) {
    for (const double target : {0.1, 0.05}) {
      std::vector<double> squared(ref.size(), 0.0);
      std::vector<bool> decided(ref.size(), true);
      for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
        RenderSettings s = settings(cover(), 4096, seed);
        s.sampler = sampler;
        s.samples = PixelErrorTarget{target, 4096};
        const RenderResult r = render(cover(), s);
        for (std::size_t p = 0; p < ref.size(); ++p) {
          const Vec3d ref_variance = reference().variance[p];
          for (std::size_t c = 0; c < 3; ++c) {
            const double d = double(r.film.pixels()[p][c]) - double(ref[p][c]);
            const double scale = double(ref[p][c]) + kRelativeErrorOffset;
            squared[p] += (d * d - ref_variance[c]) / (scale * scale) / (3.0 * kSeeds);
          }
          if (r.pixel_samples[p] <= 16 || r.pixel_samples[p] >= 4096) decided[p] = false;
        }
      }
      std::vector<double> delivered;
      for (std::size_t p = 0; p < ref.size(); ++p) {
        if (decided[p]) delivered.push_back(std::sqrt(std::max(squared[p], 0.0)) / target);
      }
      ASSERT_GT(delivered.size(), ref.size() / 5) << "the target decides a fifth of the pixels";
      std::nth_element(delivered.begin(), delivered.begin() + std::ptrdiff_t(delivered.size() / 2),
                       delivered.end());
      const double median = delivered[delivered.size() / 2];
      std::printf("%s, target %.2f: the median pixel at %.3f of it (%zu pixels decided)\n",
                  to_string(sampler).c_str(), target, median, delivered.size());
      EXPECT_GT(median, 0.85) << to_string(sampler) << " " << target << ": wastefully below it";
      EXPECT_LT(median, 1.0) << to_string(sampler) << " " << target;
    }
  }
}

TEST(IndependentSampler, RmseFallsAsOneOverTheSquareRootOfSpp) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
  for (int spp = 1; spp <= 256; spp *= 2) {
    const double x = std::log(double(spp)), y = std::log(error_of(settings(cover(), spp, 5)).rmse);
    sx += x, sy += y, sxx += x * x, sxy += x * y, n += 1;
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  EXPECT_NEAR(slope, -0.5, 0.05);
}

}  // namespace
}  // namespace rtiow
