// The denoiser (core/denoise/): what it keeps unbiased, what it keeps sharp, and whether the
// error it reports is the error it delivers. Synthetic images whose truth is known, with
// independent Gaussian halves, so every verdict is fixed by its seeds; and renders against an
// independent reference.

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <mutex>
#include <random>
#include <vector>

#include <oneapi/tbb/task_arena.h>

#include "core/denoise/denoiser.h"
#include "core/limits/error.h"
#include "core/render/denoised_output.h"
#include "core/render/render.h"
#include "core/scene/builtin_scenes.h"
#include "tests/reference_error.h"

namespace rtiow {
namespace {

struct Truth {
  int width = 64, height = 48;
  std::function<float(int x, int y)> value;  // grey: the same in R, G, B
  std::function<PixelFeatures(int x, int y)> features;
};

constexpr std::uint32_t kHalfSamples = 8;

// Two independent halves of `truth`, each a mean of kHalfSamples samples with per-sample
// standard deviation `sigma`, or `sigma` times the pixel's value where `relative`, as a render's
// noise scales with its light.
DenoiseInput noisy_halves(const Truth& truth, double sigma, std::uint64_t seed,
                          bool relative = false) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> unit(0.0, 1.0 / std::sqrt(double(kHalfSamples)));
  DenoiseInput in;
  in.width = truth.width, in.height = truth.height;
  for (int y = 0; y < truth.height; ++y) {
    for (int x = 0; x < truth.width; ++x) {
      const double t = truth.value(x, y), sd = relative ? sigma * t : sigma;
      Color a, b;
      for (std::size_t c = 0; c < 3; ++c) {
        a[c] = float(t + sd * unit(rng));
        b[c] = float(t + sd * unit(rng));
      }
      in.even.push_back(a), in.odd.push_back(b);
      in.mean.push_back((a + b) * 0.5f);
      in.even_samples.push_back(kHalfSamples), in.odd_samples.push_back(kHalfSamples);
      in.features.push_back(truth.features(x, y));
    }
  }
  return in;
}

PixelFeatures flat_features(int, int) {
  return {0.5f, 0.5f, 0.5f, 0.f, 0.f, 1.f, 4.f};
}

// The relative squared error (offset 0.01) summed over pixels and channels, true and estimated.
struct Errors {
  double truth = 0, estimate = 0;
};
Errors errors(const Truth& truth, const DenoisedImage& d, int x0, int x1) {
  Errors e;
  for (int y = 0; y < truth.height; ++y) {
    for (int x = x0; x < x1; ++x) {
      const std::size_t p = std::size_t(y) * std::size_t(truth.width) + std::size_t(x);
      for (std::size_t c = 0; c < 3; ++c) {
        const double t = truth.value(x, y), z = d.image.at(x, y)[c];
        e.truth += (z - t) * (z - t);
        e.estimate += d.mse[p][c];
      }
    }
  }
  return e;
}

TEST(Denoiser, AFlatEvenlyLitRegionStaysUnbiased) {
  const Truth flat{64, 48, [](int, int) { return 0.5f; }, flat_features};
  double sum = 0, count = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const DenoisedImage d = denoise(noisy_halves(flat, 0.4, seed));
    for (const Color& c : d.image.pixels()) sum += double(c.x + c.y + c.z), count += 3;
  }
  // The noisy mean's standard error over the 4 images is 0.4 / sqrt(16 * 4 * 64 * 48 * 3):
  // about 6e-4. A filter that averages moves nothing; a bias (a clamp, a weight that favours
  // bright neighbours) would show as many of these.
  const double mean = sum / count;
  EXPECT_NEAR(mean, 0.5, 4 * 0.4 / std::sqrt(16.0 * count));
}

TEST(Denoiser, FilteringHelpsWhereTheImageIsSmooth) {
  const Truth ramp{64, 48, [](int x, int) { return 0.2f + 0.01f * float(x); }, flat_features};
  const DenoisedImage d = denoise(noisy_halves(ramp, 0.4, 7));
  Errors noisy;
  for (int y = 0; y < ramp.height; ++y)
    for (int x = 0; x < ramp.width; ++x)
      for (std::size_t c = 0; c < 3; ++c) {
        const double e = d.noisy.at(x, y)[c] - ramp.value(x, y);
        noisy.truth += e * e;
      }
  const Errors denoised = errors(ramp, d, 0, ramp.width);
  EXPECT_LT(denoised.truth, noisy.truth / 4) << "the ramp is what a first-order regression fits";
  EXPECT_LT(d.estimated_error, d.noisy_error);
}

// An edge the features know (albedo) and one they know by depth and normal alone (a
// silhouette): the error across it stays within what the denoiser reports there, and the
// pixels beside it keep their side's value.
void expect_sharp(const Truth& edge, int edge_x, const char* what) {
  double truth = 0, estimate = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const DenoisedImage d = denoise(noisy_halves(edge, 0.3, seed));
    const Errors across = errors(edge, d, edge_x - 2, edge_x + 2);
    truth += across.truth, estimate += across.estimate;
    double left = 0, right = 0;
    for (int y = 0; y < edge.height; ++y)
      left += d.image.at(edge_x - 1, y).x, right += d.image.at(edge_x, y).x;
    const double step = edge.value(edge_x, 0) - edge.value(edge_x - 1, 0);
    EXPECT_NEAR(left / edge.height, edge.value(edge_x - 1, 0), 0.1 * std::abs(step)) << what;
    EXPECT_NEAR(right / edge.height, edge.value(edge_x, 0), 0.1 * std::abs(step)) << what;
  }
  EXPECT_LT(truth, 2 * estimate) << what << ": the error across the edge is above its estimate";
}

TEST(Denoiser, AnAlbedoEdgeStaysSharp) {
  const Truth edge{64, 48, [](int x, int) { return x < 32 ? 0.15f : 0.75f; },
                   [](int x, int) -> PixelFeatures {
                     const float a = x < 32 ? 0.2f : 0.9f;
                     return {a, a, a, 0.f, 0.f, 1.f, 4.f};
                   }};
  expect_sharp(edge, 32, "albedo edge");
}

TEST(Denoiser, ASilhouetteStaysSharp) {
  const Truth silhouette{64, 48, [](int x, int) { return x < 24 ? 0.7f : 0.25f; },
                         [](int x, int) -> PixelFeatures {
                           if (x < 24) return {0.5f, 0.5f, 0.5f, 0.6f, 0.f, 0.8f, 2.f};
                           return {0.5f, 0.5f, 0.5f, 0.f, 1.f, 0.f, 9.f};
                         }};
  expect_sharp(silhouette, 24, "silhouette");
}

TEST(Denoiser, NeverWorseThanTheNoisyImageWhereTheFeaturesSayNothing) {
  // Detail the features do not explain (a checkerboard of one material), under little noise:
  // filtering would blur it, so the pixels keep their noisy values.
  const Truth checks{64, 48, [](int x, int y) { return ((x + y) % 2) ? 0.2f : 0.8f; },
                     flat_features};
  const DenoisedImage d = denoise(noisy_halves(checks, 0.05, 3));
  Errors noisy;
  for (int y = 0; y < checks.height; ++y)
    for (int x = 0; x < checks.width; ++x)
      for (std::size_t c = 0; c < 3; ++c) {
        const double e = d.noisy.at(x, y)[c] - checks.value(x, y);
        noisy.truth += e * e;
      }
  const Errors denoised = errors(checks, d, 0, checks.width);
  EXPECT_LT(denoised.truth, 1.1 * noisy.truth);
}

// An image with what a render has (smooth shading, edges the features know, detail they do
// not): over seeds, the error the denoiser reports is the error it delivers.
TEST(Denoiser, TheErrorItReportsIsTheErrorItDelivers) {
  const Truth scene{96, 64,
                    [](int x, int y) {
                      const float shade = 0.3f + 0.4f * float(y) / 64.0f;
                      const float ball =
                          (x - 60) * (x - 60) + (y - 30) * (y - 30) < 400 ? 1.6f : 1.0f;
                      const float stripes = (x / 4) % 2 ? 0.1f : 0.0f;  // not in the features
                      return shade * ball * (x < 30 ? 0.3f : 1.0f) + stripes;
                    },
                    [](int x, int y) -> PixelFeatures {
                      const bool ball = (x - 60) * (x - 60) + (y - 30) * (y - 30) < 400;
                      const float a = x < 30 ? 0.3f : 1.0f;
                      if (ball)
                        return {a, a, a, float(x - 60) / 20.f, float(y - 30) / 20.f, 0.5f, 3.f};
                      return {a, a, a, 0.f, 1.f, 0.f, 6.f};
                    }};
  double truth = 0, estimate = 0;
  for (std::uint64_t seed = 11; seed <= 14; ++seed) {
    const DenoisedImage d = denoise(noisy_halves(scene, 0.5, seed));
    for (int y = 0; y < scene.height; ++y) {
      for (int x = 0; x < scene.width; ++x) {
        const double t = scene.value(x, y), level = (t + 0.01) * (t + 0.01);
        for (std::size_t c = 0; c < 3; ++c) {
          const double e = d.image.at(x, y)[c] - t;
          truth += e * e / level;
        }
      }
    }
    estimate += d.estimated_error * d.estimated_error * 3.0 * scene.width * scene.height;
  }
  const double ratio = std::sqrt(estimate / truth);
  std::printf("estimated over true image error: %.3f\n", ratio);
  EXPECT_GT(ratio, 0.8);
  EXPECT_LT(ratio, 1.25);
}

// The per-pixel error channel, summed over a region and read relative to the image as the
// image's error is, reads that region's error: here a dark region beside a bright one, whose
// squared errors are 2,500 times the dark one's. Averaged as they were, the bright pixels'
// errors landed on their dark neighbours and the channel read 15 times the dark region's error;
// now 1.5: where the features explain the image the filter leaves little error, and the
// channel's floor at 0 (each pixel's own estimate is noise about it) lifts the average.
TEST(Denoiser, ItsErrorChannelReadsADarkRegionBesideABrightOne) {
  const Truth halves{64, 48, [](int x, int) { return x < 32 ? 0.02f : 1.0f; },
                     [](int x, int) -> PixelFeatures {
                       const float a = x < 32 ? 0.02f : 1.0f;
                       return {a, a, a, 0.f, 0.f, 1.f, 4.f};
                     }};
  double truth = 0, estimate = 0;
  for (std::uint64_t seed = 21; seed <= 24; ++seed) {
    const DenoisedImage d = denoise(noisy_halves(halves, 0.5, seed, true));
    for (int y = 0; y < halves.height; ++y) {
      for (int x = 0; x < 32; ++x) {
        const double t = halves.value(x, y);
        for (std::size_t c = 0; c < 3; ++c) {
          const double e = d.image.at(x, y)[c] - t;
          truth += e * e / ((t + 0.01) * (t + 0.01));
        }
      }
    }
    estimate += channel_relative_squared_error(d, 0, 0, 32, halves.height);
  }
  const double ratio = std::sqrt(estimate / truth);
  std::printf("the dark region's error from the channel over its true error: %.3f\n", ratio);
  EXPECT_GT(ratio, 0.7);
  EXPECT_LT(ratio, 2.0);
}

// The same against independent renders: the cover at 16 spp, three seeds, against a 1024-spp
// reference whose own noise (its halves' estimate) is taken out of the true error.
// The cover at 48x32 and 8 spp, as a render with --denoise keeps it.
DenoiseInput small_cover_input() {
  RenderSettings s;
  s.width = 48, s.height = 32, s.samples = FixedSamples{8};
  s.estimate_error = true, s.passes = {true, true, true};
  return denoise_input(render(make_builtin_scene("cover", 1), s));
}

// docs/denoising.md has the study at other counts, sizes and scenes, where it reads low.
TEST(Denoiser, TheCoversReportedErrorIsItsErrorAgainstAReference) {
  const Scene scene = make_builtin_scene("cover", 1);
  RenderSettings s;
  s.width = 96, s.height = 64, s.estimate_error = true, s.passes = {true, true, true};
  s.samples = FixedSamples{1024}, s.seed = 1000;
  const DenoiseInput reference = denoise_input(render(scene, s));
  double truth = 0, estimate = 0, channel = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    s.samples = FixedSamples{16}, s.seed = seed;
    const DenoisedImage d = denoise(denoise_input(render(scene, s)));
    truth += true_relative_squared_error(reference, d.image.pixels());
    estimate += d.estimated_error * d.estimated_error * 3.0 * double(reference.size());
    channel += channel_relative_squared_error(d, 0, 0, s.width, s.height);
  }
  const double ratio = std::sqrt(estimate / truth), channel_ratio = std::sqrt(channel / truth);
  std::printf("cover, 16 spp: estimated over true image error %.3f, from the channel %.3f\n", ratio,
              channel_ratio);
  EXPECT_GT(ratio, 0.8);
  EXPECT_LT(ratio, 1.25);
  // The channel's floor at 0 lifts it a little (docs/denoising.md); averaged as squared errors
  // rather than relative ones it read 2.33 times the truth here (now 0.97).
  EXPECT_GT(channel_ratio, 0.8);
  EXPECT_LT(channel_ratio, 1.4);
}

TEST(Denoiser, TheSameBitsOnAnyNumberOfThreads) {
  const Scene scene = make_builtin_scene("cover", 1);
  RenderSettings s;
  s.width = 48, s.height = 32, s.samples = FixedSamples{8};
  s.estimate_error = true, s.passes = {true, true, true};
  s.threads = 1;
  const DenoisedImage one = denoise(denoise_input(render(scene, s)));
  s.threads = 2;
  const DenoisedImage two = denoise(denoise_input(render(scene, s)));
  EXPECT_EQ(one.image.pixels(), two.image.pixels());
  EXPECT_EQ(one.estimated_error, two.estimated_error);
  // The denoiser's own threads: every pass, the blend and the window means.
  const DenoiseInput in = small_cover_input();
  const auto denoised_on = [&](int threads) {
    DenoisedImage d;
    tbb::task_arena(threads).execute([&] { d = denoise(in); });
    return d;
  };
  const DenoisedImage alone = denoised_on(1);
  for (const int threads : {2, 3}) {
    const DenoisedImage d = denoised_on(threads);
    EXPECT_EQ(d.image.pixels(), alone.image.pixels()) << threads << " threads";
    EXPECT_EQ(d.mse, alone.mse) << threads << " threads";
    EXPECT_EQ(d.noisy_kept, alone.noisy_kept) << threads << " threads";
    EXPECT_EQ(d.estimated_error, alone.estimated_error) << threads << " threads";
  }
}

// Images smaller than its windows (a 3-pixel-wide crop, a 1x1 render): each window is clipped
// to the image, and a noiseless flat image comes back as it went in, whatever its features.
TEST(Denoiser, ImagesSmallerThanItsWindowsComeBackWhole) {
  for (int width = 1; width <= 7; ++width) {
    for (int height = 1; height <= 7; ++height) {
      DenoiseInput in;
      in.width = width, in.height = height;
      for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
          const Color flat{0.3f, 0.3f, 0.3f};
          in.even.push_back(flat), in.odd.push_back(flat), in.mean.push_back(flat);
          in.even_samples.push_back(kHalfSamples), in.odd_samples.push_back(kHalfSamples);
          const float albedo = 0.2f + 0.1f * float((x + 2 * y) % 5);
          in.features.push_back({albedo, 0.5f, 0.5f, 0.f, 0.f, 1.f, 4.f + float(x)});
        }
      }
      const DenoisedImage d = denoise(in);
      for (const Color& c : d.image.pixels())
        for (std::size_t i = 0; i < 3; ++i)
          ASSERT_NEAR(c[i], 0.3f, 1e-5f) << width << "x" << height;
      EXPECT_TRUE(std::isfinite(d.estimated_error)) << width << "x" << height;
    }
  }
}

// Its caller may stop it (a render's stop or time limit while it judges a round): asked
// between rows, it throws soon after; never asked to stop, the same bits as without the question.
TEST(Denoiser, StopsWhenItsCallerSaysSo) {
  const DenoiseInput in = small_cover_input();
  std::atomic<int> asked{0};
  EXPECT_THROW(denoise(in, {[&] { return ++asked > 40; }}), DenoiseCancelled);
  EXPECT_LT(asked.load(), 4 * 32);  // it stopped within the pass it was in
  const DenoisedImage plain = denoise(in), asked_never = denoise(in, {[] { return false; }});
  EXPECT_EQ(plain.image.pixels(), asked_never.image.pixels());
}

// What a display shows of a denoise: its work done rises from 0, never past the whole, and is
// the whole when the image is made; watched, the image is the same bits.
TEST(Denoiser, ItsProgressReachesTheWholeAsItEnds) {
  const DenoiseInput in = small_cover_input();
  WorkProgress progress;
  progress.done = 12345;  // a display's counters from an earlier denoise start again
  std::mutex mutex;       // asked from every thread of the passes
  std::vector<std::uint64_t> seen;
  const auto ask = [&] {
    const std::lock_guard lock(mutex);
    seen.push_back(progress.done.load());
    return false;
  };
  const DenoisedImage watched = denoise(in, {ask, &progress});
  ASSERT_GT(progress.total.load(), 0u);
  EXPECT_EQ(progress.done.load(), progress.total.load());
  EXPECT_NE(progress.start_ns.load(), 0);
  ASSERT_FALSE(seen.empty());
  EXPECT_LT(seen.front(), progress.total.load() / 10) << "it began from the start";
  for (const std::uint64_t done : seen) EXPECT_LE(done, progress.total.load());
  EXPECT_EQ(watched.image.pixels(), denoise(in).image.pixels());
}

TEST(Denoiser, RefusesARenderWithoutHalvesOrFirstHits) {
  const Scene scene = make_builtin_scene("materials", 1);
  RenderSettings s;
  s.width = 16, s.height = 9, s.samples = FixedSamples{4};
  s.passes = {true, true, true};
  EXPECT_THROW(denoise_input(render(scene, s)), InvalidInput);  // one Sobol sequence
  s.estimate_error = true, s.passes = {};
  EXPECT_THROW(denoise_input(render(scene, s)), InvalidInput);  // no first hits
}

}  // namespace
}  // namespace rtiow
