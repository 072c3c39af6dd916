// End-to-end: every built-in scene renders at a tiny size to a plausible image, and the
// image is bit-identical for 1 and 2 threads and for both accelerators.

#include <gtest/gtest.h>
#include <oneapi/tbb/task_arena.h>
#include <xmmintrin.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <utility>
#include <variant>
#include <vector>

#include "core/accel/naive_accel.h"
#include "core/limits/error.h"
#include "core/render/integrator.h"
#include "core/render/render.h"
#include "core/render/render_loop.h"
#include "core/render/render_outcome.h"
#include "core/render/render_state.h"
#include "core/render/sample_allocation.h"
#include "core/scene/builtin_scenes.h"
#include "core/scene/camera.h"
#include "core/scene_file/material_json.h"
#include "tests/closed_room.h"
#include "tests/film_equality.h"

namespace rtiow {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

RenderSettings tiny(const Scene& scene) {
  RenderSettings s;
  s.width = 48;
  s.height = std::max(1, int(std::lround(48 / scene.image.aspect_ratio)));
  s.samples = FixedSamples{4};
  s.max_depth = 12;
  s.seed = 11;
  s.sampler = SamplerKind::Independent;
  return s;
}

// The same render with 1 thread, 2 threads and the naive intersector: all must agree.
struct ThreeWays {
  RenderResult one, two, naive;
};

ThreeWays render_three_ways(const Scene& scene, RenderSettings settings) {
  ThreeWays r;
  settings.threads = 1;
  r.one = render(scene, settings);
  settings.threads = 2;
  r.two = render(scene, settings);
  settings.accel = AccelKind::Naive;
  r.naive = render(scene, settings);
  return r;
}

class EveryScene : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryScene, RendersFiniteNonBlackAndDeterministic) {
  const Scene scene = make_builtin_scene(GetParam(), 1);
  const RenderSettings settings = tiny(scene);
  const auto [one, two, naive] = render_three_ways(scene, settings);

  double sum = 0;
  for (const Color& c : one.film.pixels()) {
    ASSERT_TRUE(is_finite(c));
    ASSERT_GE(std::min({c.x, c.y, c.z}), 0.0f);
    sum += c.x + c.y + c.z;
  }
  const double mean = sum / (3.0 * double(one.film.pixels().size()));
  EXPECT_GT(mean, 0.1) << "image is (nearly) black";
  EXPECT_LT(mean, 1.0) << "image is washed out";
  EXPECT_GT(one.rays_traced, std::uint64_t(settings.width * settings.height * 4));

  EXPECT_TRUE(test::bit_identical(one.film, two.film)) << "1 and 2 threads differ";
  EXPECT_TRUE(test::bit_identical(one.film, naive.film)) << "Embree and naive differ";
  EXPECT_EQ(one.rays_traced, naive.rays_traced);
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, EveryScene,
                         ::testing::Values("materials", "wide-angle", "viewpoint", "viewpoint-zoom",
                                           "defocus", "cover"),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                           std::string name = param_info.param;
                           for (char& c : name) c = (c == '-') ? '_' : c;
                           return name;
                         });

// The Sobol samplers, every adaptive mode and the book's estimator (no roulette) keep the
// guarantee: the same image for any thread count and either accelerator (adaptive decisions
// are taken between rounds, from counts, sums and ray counts that do not depend on the
// schedule).
TEST(Render, SobolAndAdaptiveRendersAreDeterministic) {
  const Scene scene = make_builtin_scene("cover", 1);
  enum Mode { kSobol, kPaddedSobol, kTargetError, kImageError, kBudget, kNoRoulette };
  for (const Mode mode : {kSobol, kPaddedSobol, kTargetError, kImageError, kBudget, kNoRoulette}) {
    RenderSettings settings = tiny(scene);
    settings.russian_roulette = mode != kNoRoulette;
    settings.sampler = mode == kPaddedSobol ? SamplerKind::PaddedSobol
                       : mode == kSobol     ? SamplerKind::Sobol
                                            : SamplerKind::Independent;
    const bool adaptive = mode >= kTargetError && mode <= kBudget;
    settings.samples = mode == kTargetError  ? SampleBudget(PixelErrorTarget{0.15, 128})
                       : mode == kImageError ? SampleBudget(ImageErrorTarget{0.08, 128})
                       : mode == kBudget     ? SampleBudget(AdaptiveBudget{48})
                                             : SampleBudget(FixedSamples{8});
    const auto [one, two, naive] = render_three_ways(scene, settings);
    EXPECT_TRUE(test::bit_identical(one.film, two.film)) << "mode " << mode;
    EXPECT_TRUE(test::bit_identical(one.film, naive.film)) << "mode " << mode;
    EXPECT_EQ(one.pixel_samples, two.pixel_samples);
    if (adaptive) {
      const auto [least, most] =
          std::minmax_element(one.pixel_samples.begin(), one.pixel_samples.end());
      EXPECT_GE(*least, 16u) << "mode " << mode;
      EXPECT_GT(*most, *least) << "mode " << mode << ": pixels must get different counts";
      if (mode != kBudget) {
        EXPECT_LE(*most, 128u) << "mode " << mode;
      }
    }
  }
}

// The region of `whole` that `crop` covers.
Film region_of(const Film& whole, const PixelRegion& crop) {
  Film region(crop.width(), crop.height());
  for (int y = 0; y < crop.height(); ++y) {
    for (int x = 0; x < crop.width(); ++x) region.at(x, y) = whole.at(crop.x0 + x, crop.y0 + y);
  }
  return region;
}

// A crop renders the whole image's pixels in its region, bit for bit: with either sampler, a
// lens (the defocus scene), 1 or 2 threads or the naive intersector, a share of the samples,
// and any region (the whole frame, an inner block, one corner pixel, a column).
// A library render stopped through RenderProgress says why as its caller said it, or "stopped
// on request"; it recorded "interrupted by a signal" whoever stopped it (issue 70).
TEST(Render, AStoppedRenderSaysTheCauseItsCallerGave) {
  const Scene scene = make_builtin_scene("cover", 1);
  for (const bool adaptive : {false, true}) {
    RenderSettings settings;
    settings.width = 16, settings.height = 9, settings.max_depth = 8;
    settings.samples = adaptive ? SampleBudget(ImageErrorTarget{0.001, 1024}) : FixedSamples{512};
    RenderProgress asked;
    asked.stop_requested = true;  // honoured after the first pass or round
    const RenderResult quiet = render(scene, settings, &asked);
    ASSERT_TRUE(quiet.stopped) << adaptive;
    EXPECT_EQ(describe_outcome(settings, quiet).stopped, "stopped on request") << adaptive;

    RenderProgress closed;
    closed.stop_requested = true;
    closed.stop_cause = "the viewer's window was closed";
    const RenderResult result = render(scene, settings, &closed);
    EXPECT_EQ(describe_outcome(settings, result).stopped, "the viewer's window was closed");
    const RenderResult whole = render(scene, settings);
    EXPECT_FALSE(whole.stopped);
    EXPECT_EQ(describe_outcome(settings, whole).stopped, "") << adaptive;
  }
}

// An image error target stopped in a round after a judgement: its estimate is that of the
// sums it ends with, not its last judgement's of the fewer samples before the round (the
// summary said "not reached: 0.0406 at 128 spp" of an estimate made at fewer).
TEST(Render, AnImageErrorTargetEndedInARoundReportsTheErrorOfItsFinishedSums) {
  const Scene scene = make_builtin_scene("cover", 1);
  RenderSettings s = tiny(scene);
  s.sampler = SamplerKind::Sobol, s.estimate_error = true;
  s.samples = ImageErrorTarget{0.001, 1024, 8};
  std::optional<RenderState> judged, finished;
  RenderProgress progress;
  Checkpointing keep;
  keep.interval_seconds = 1e-9;  // a save after every group of pixels
  keep.save = [&](const RenderState& state, SaveReason reason) {
    const auto [least, most] =
        std::minmax_element(state.pixels.samples.begin(), state.pixels.samples.end());
    if (reason == SaveReason::Stopped) finished = state;
    if (*most == 8 && *least == 8) judged = state;  // the first round's end, which was judged
    if (*most > 8 && judged) progress.stop_requested = true;  // in the second round
  };
  const RenderResult r = render(scene, s, &progress, &keep);
  ASSERT_TRUE(r.stopped);
  ASSERT_TRUE(judged && finished);
  const auto estimate = [&](const RenderState& state) {
    return std::sqrt(
        estimated_rel_mse(pooled_estimates(s, state.pixels).variance, state.pixels.samples));
  };
  ASSERT_NE(finished->pixels.samples, judged->pixels.samples);
  EXPECT_EQ(r.estimated_image_error, estimate(*finished));
  EXPECT_NE(r.estimated_image_error, estimate(*judged));
  EXPECT_EQ(r.error_estimate, ErrorEstimate::Calibrated);
}

// A pixel error target stopped in a round counts every pixel still above the target in the sums
// it ends with: its judgements counted only those at the cap, so a render its time limit cut
// short said "target error 0.01" with 0 pixels above it.
TEST(Render, APixelErrorTargetEndedInARoundCountsThePixelsAboveIt) {
  const Scene scene = make_builtin_scene("cover", 1);
  RenderSettings s = tiny(scene);
  s.sampler = SamplerKind::Sobol, s.estimate_error = true;
  s.samples = PixelErrorTarget{0.01, 1024, 8};
  std::optional<RenderState> finished;
  RenderProgress progress;
  Checkpointing keep;
  keep.interval_seconds = 1e-9;  // a save after every group of pixels
  keep.save = [&](const RenderState& state, SaveReason reason) {
    if (reason == SaveReason::Stopped) finished = state;
    const auto most = *std::max_element(state.pixels.samples.begin(), state.pixels.samples.end());
    if (most > 8) progress.stop_requested = true;  // in the second round, far below the cap
  };
  const RenderResult r = render(scene, s, &progress, &keep);
  ASSERT_TRUE(r.stopped);
  ASSERT_TRUE(finished);
  const std::vector<double> variance =
      neighbourhood_relative_variance(s, finished->pixels, Pooling::Median);
  std::uint64_t above = 0;
  for (std::size_t p = 0; p < variance.size(); ++p)
    above += variance[p] / double(finished->pixels.samples[p]) > 0.01 * 0.01 ? 1 : 0;
  EXPECT_GT(above, 0u);
  EXPECT_EQ(r.pixels_above_target, above);
  EXPECT_FALSE(error_target_reached(s, r));
  EXPECT_NE(describe_outcome(s, r).samples.find("target error 0.01 not reached by " +
                                                std::to_string(above) + " pixels"),
            std::string::npos)
      << describe_outcome(s, r).samples;
}

TEST(Render, ACropIsTheWholeImagesRegionBitForBit) {
  const Scene scene = make_builtin_scene("defocus", 1);
  for (const SamplerKind sampler : {SamplerKind::Independent, SamplerKind::Sobol}) {
    for (const std::uint64_t first : {std::uint64_t(0), std::uint64_t(3)}) {
      RenderSettings whole = tiny(scene);
      whole.sampler = sampler;
      whole.first_sample = first;
      whole.samples = FixedSamples{5};
      const RenderResult full = render(scene, whole);
      const int w = whole.width, h = whole.height;
      for (const PixelRegion crop : {PixelRegion{0, 0, w, h}, PixelRegion{3, 2, 17, 11},
                                     PixelRegion{w - 1, h - 1, w, h}, PixelRegion{5, 0, 6, h}}) {
        SCOPED_TRACE(to_string(crop) + " " + to_string(sampler) + " from " + std::to_string(first));
        RenderSettings cropped = whole;
        cropped.crop = crop;
        const auto [one, two, naive] = render_three_ways(scene, cropped);
        const Film expected = region_of(full.film, crop);
        EXPECT_TRUE(test::bit_identical(one.film, expected));
        EXPECT_TRUE(test::bit_identical(two.film, expected));
        EXPECT_TRUE(test::bit_identical(naive.film, expected));
        EXPECT_EQ(one.pixel_samples.size(), std::size_t(crop.width() * crop.height()));
      }
    }
  }
}

TEST(Render, ACropOutsideTheFrameOrOfAnAdaptiveRenderIsRefused) {
  const Scene scene = make_builtin_scene("cover", 1);
  RenderSettings s = tiny(scene);
  for (const PixelRegion crop : {PixelRegion{0, 0, s.width + 1, 4}, PixelRegion{4, 4, 4, 8},
                                 PixelRegion{-1, 0, 3, 3}, PixelRegion{0, 3, 3, 2}}) {
    s.crop = crop;
    EXPECT_THROW(render(scene, s), InvalidInput) << to_string(crop);
  }
  s.crop = PixelRegion{0, 0, 4, 4};
  s.samples = PixelErrorTarget{0.1, 64};
  try {
    render(scene, s);
    ADD_FAILURE() << "an adaptive crop was rendered";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("uniform sampling only"), std::string::npos) << e.what();
  }
}

// --target-error's contract, exactly: when it ends (no time limit), every pixel below the
// maximum has a relative standard error pooled from its neighbours (their median) at or below
// the target, judged on the final image (a later round may reopen a pixel whose neighbours
// changed). Some pixels stop between the minimum and the maximum, so the check is not vacuous.
TEST(Render, TargetErrorStopsEveryPixelAtItsTarget) {
  const Scene scene = make_builtin_scene("cover", 1);
  RenderSettings s = tiny(scene);  // 48x27
  const PixelErrorTarget target{0.15, 1024};
  s.samples = target;
  s.max_depth = 50;
  s.seed = 5;
  const RenderResult r = render(scene, s);
  PixelAccumulators pixels(r.pixel_samples.size());
  pixels.sums = r.sums;
  pixels.samples = r.pixel_samples;
  const std::vector<double> judged = neighbourhood_relative_variance(s, pixels, Pooling::Median);
  const double target_variance = target.error * target.error;
  int between = 0;
  double closest = 0;
  for (std::size_t p = 0; p < judged.size(); ++p) {
    const std::uint32_t n = r.pixel_samples[p];
    if (n >= std::uint32_t(target.most)) continue;
    const double ratio = judged[p] / double(n) / target_variance;
    EXPECT_LE(ratio, 1.0) << "pixel " << p << " stopped at " << n << " samples";
    between += n > std::uint32_t(target.least);
    closest = std::max(closest, ratio);
  }
  EXPECT_GT(between, 100);
  EXPECT_GT(closest, 0.9) << "the pixels nearest their target";
}

TEST(Render, DifferentSeedsGiveDifferentNoise) {
  const Scene scene = make_builtin_scene("materials", 1);
  RenderSettings settings = tiny(scene);
  const RenderResult a = render(scene, settings);
  settings.seed = 12;
  const RenderResult b = render(scene, settings);
  EXPECT_FALSE(test::bit_identical(a.film, b.film));
}

// Shares of a render add up to the whole render, bit for bit: the exact sums make the split
// (passes, processes, machines) invisible.
TEST(Render, SharesOfTheSamplesAddUpToTheWholeRender) {
  const Scene scene = make_builtin_scene("cover", 1);
  RenderSettings whole = tiny(scene);
  whole.samples = FixedSamples{9};
  const RenderResult all = render(scene, whole);
  std::vector<PixelSum> sums(all.sums.size());  // the colour's
  std::uint64_t rays = 0;
  for (auto [first, count] : {std::pair{0, 2}, std::pair{2, 5}, std::pair{7, 2}}) {
    RenderSettings share = whole;
    share.first_sample = std::uint64_t(first);
    share.samples = FixedSamples{count};
    const RenderResult part = render(scene, share);
    for (std::size_t i = 0; i < sums.size(); ++i) sums[i] += part.sums.color[i];
    rays += part.rays_traced;
  }
  EXPECT_TRUE(sums == all.sums.color);
  EXPECT_EQ(rays, all.rays_traced);
  Film merged(whole.width, whole.height);
  for (int y = 0; y < whole.height; ++y) {
    for (int x = 0; x < whole.width; ++x)
      merged.at(x, y) = sums[std::size_t(y * whole.width + x)].mean(9);
  }
  EXPECT_TRUE(test::bit_identical(merged, all.film));
}

// A pass sends the camera rays of a row's pixels to the accelerator in packets that, below
// eight samples per pixel, hold several pixels: every pixel must still get its own samples,
// exactly what rendering it alone gives.
TEST(Render, PacketsOfSeveralPixelsGiveEachPixelItsOwnSamples) {
  const Scene scene = make_builtin_scene("cover", 1);
  RenderSettings settings = tiny(scene);
  settings.samples = FixedSamples{3};  // a packet of 8: two pixels and a part of a third
  settings.accel = AccelKind::Naive;
  const RenderResult whole = render(scene, settings);
  const Camera camera(scene.camera, settings.width, settings.height);
  const NaiveAccel accel(scene.spheres);
  const RenderContext<NaiveAccel> ctx{scene, camera, accel, settings};
  std::uint64_t rays = 0;
  for (int y = 0; y < settings.height; ++y) {
    for (int x = 0; x < settings.width; ++x) {
      PixelSum sum;
      PixelSpread spread;
      std::uint64_t pixel_rays = 0;
      rays += accumulate_run(ctx, PixelRun{x, y, 1, 0, 3}, {&sum, &spread, &pixel_rays});
      const std::size_t p = std::size_t(y * settings.width + x);
      ASSERT_TRUE(sum == whole.sums.color[p]) << "pixel " << x << "," << y;
      ASSERT_TRUE(spread == whole.sums.spreads[p]) << "pixel " << x << "," << y;
    }
  }
  EXPECT_EQ(rays, whole.rays_traced);
}

// A small image on many threads is cut into 8x8 tiles instead of 16x16, and renders the
// same bits as one thread with 16x16 tiles.
TEST(Render, FinerTilesForManyThreadsGiveTheSameImage) {
  EXPECT_EQ(tile_size(400, 225, 2), 16);
  EXPECT_EQ(tile_size(400, 225, 64), 8);
  EXPECT_EQ(tile_size(48, 32, 1), 8);  // 6 tiles of 16: fewer than 8 for even one thread
  const Scene scene = make_builtin_scene("cover", 1);
  RenderSettings settings = tiny(scene);
  settings.width = 144, settings.height = 96;  // 54 tiles of 16x16
  settings.threads = 1;
  ASSERT_EQ(tile_size(settings.width, settings.height, 1), 16);
  const RenderResult one = render(scene, settings);
  settings.threads = 8;
  ASSERT_EQ(tile_size(settings.width, settings.height, 8), 8);
  const RenderResult many = render(scene, settings);
  ASSERT_EQ(one.sums.size(), many.sums.size());
  for (std::size_t p = 0; p < one.sums.size(); ++p) {
    ASSERT_TRUE(one.sums.color[p] == many.sums.color[p]) << "pixel " << p;
    ASSERT_TRUE(one.sums.spreads[p] == many.sums.spreads[p]) << "pixel " << p;
  }
  EXPECT_EQ(one.rays_traced, many.rays_traced);
}

TEST(PixelSum, RoundsEachSampleOnceAndClampsTheAbsurd) {
  PixelSum s;
  s.add({0.25f, 1.0f, 0.0f});
  s.add({0.75f, std::numeric_limits<float>::quiet_NaN(), -3.0f});
  const Color mean = s.mean(2);
  EXPECT_EQ(mean.x, 0.5f);
  EXPECT_EQ(mean.y, 0.5f) << "NaN counts as 0";
  EXPECT_EQ(mean.z, 0.0f) << "negative counts as 0";
  PixelSum big;
  big.add({1e30f, 0, 0});
  EXPECT_EQ(big.mean(1).x, float(PixelSum::kMaxSample));
}

TEST(Render, DepthZeroIsBlackAsInTheBook) {
  const Scene scene = make_builtin_scene("materials", 1);
  RenderSettings settings = tiny(scene);
  settings.max_depth = 0;
  const RenderResult r = render(scene, settings);
  for (const Color& c : r.film.pixels()) ASSERT_EQ(c, (Color{0, 0, 0}));
  EXPECT_EQ(r.rays_traced, 0u);
}

// The depth limit, exactly: inside a closed white diffuse sphere no path escapes, is absorbed
// or plays the roulette (its throughput stays 1), so every path traces exactly max_depth rays
// and ends black. One bounce more or less changes the count by a sample's worth.
TEST(Render, EveryPathTracesExactlyMaxDepthRaysInAClosedRoom) {
  const Scene room = closed_room(Lambertian{{1.0f, 1.0f, 1.0f}});
  RenderSettings settings = tiny(room);
  for (int depth : {1, 2, 5}) {
    settings.max_depth = depth;
    const RenderResult r = render(room, settings);
    const std::uint64_t samples = std::uint64_t(settings.width) * std::uint64_t(settings.height) *
                                  std::uint64_t(std::get<FixedSamples>(settings.samples).per_pixel);
    EXPECT_EQ(r.rays_traced, std::uint64_t(depth) * samples) << "depth " << depth;
    for (const Color& c : r.film.pixels()) ASSERT_EQ(c, (Color{0, 0, 0})) << "depth " << depth;
  }
}

// The sample layout is the integrator's: a path draws the camera's dimensions and then the
// same number per bounce whatever it hits. In closed white rooms every ray hits and no path
// plays the roulette, so a path of depth D always draws camera + D bounces, for each material
// and each sampler.
TEST(Render, EveryBounceDrawsTheSameDimensionsWhateverTheMaterial) {
  const Material materials[] = {Lambertian{{1.0f, 1.0f, 1.0f}}, make_metal({1, 1, 1}, 0.3f),
                                make_metal({1, 1, 1}, 0.0f), Dielectric{1.5f}};
  for (const Material& inner : materials) {
    Scene room = closed_room(Lambertian{{1.0f, 1.0f, 1.0f}});
    room.spheres.add({0, 0, -20}, 10.0f, room.add_material(inner));
    const NaiveAccel accel(room.spheres);
    for (const SamplerKind kind :
         {SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::PaddedSobol}) {
      for (std::uint64_t sample = 0; sample < 16; ++sample) {
        const RoomPath path = trace_from_centre(room, accel, kind, sample, 7);
        EXPECT_EQ(path.rays, 7u) << "every ray hits a wall or the inner sphere";
        EXPECT_EQ(path.dimensions, bounce_dimension(7)) << to_string(kind);
      }
    }
  }
}

TEST(Render, CoverLayoutFollowsTheSceneSeed) {
  const Scene a = make_builtin_scene("cover", 1), b = make_builtin_scene("cover", 1),
              c = make_builtin_scene("cover", 2);
  EXPECT_EQ(a.spheres.center_x, b.spheres.center_x);
  EXPECT_NE(a.spheres.center_x, c.spheres.center_x);
  // The book's grid: 484 candidates, a few dropped near the big metal sphere, plus 4.
  EXPECT_GT(a.spheres.size(), 470u);
  EXPECT_LE(a.spheres.size(), 488u);
}

TEST(Render, SphereFieldHasExactlyNSmallSpheres) {
  for (std::uint64_t n : {1u, 10u, 999u, 20000u}) {
    const Scene s = make_builtin_scene("spheres:" + std::to_string(n), 1);
    EXPECT_EQ(s.spheres.size(), n + 4) << "N small + ground + 3 big";
    // No small sphere intersects a big one.
    for (std::size_t i = 1; i <= n; ++i) {
      for (std::size_t big = n + 1; big < n + 4; ++big) {
        ASSERT_GT(length(s.spheres.center(i) - s.spheres.center(big)), 1.2f);
      }
    }
  }
}

// spheres:N is made in parallel, each sphere from its own stream: the same scene from one
// thread as from several, and another scene from another seed.
TEST(Render, SphereFieldIsTheSameForAnyThreadCount) {
  const auto make_with = [](int threads, std::uint64_t seed) {
    tbb::task_arena arena(threads);
    return arena.execute([&] { return make_builtin_scene("spheres:30000", seed); });
  };
  const Scene one = make_with(1, 1), two = make_with(2, 1), other = make_with(2, 2);
  EXPECT_EQ(one.spheres.center_x, two.spheres.center_x);
  EXPECT_EQ(one.spheres.center_z, two.spheres.center_z);
  EXPECT_EQ(one.spheres.material, two.spheres.material);
  ASSERT_EQ(one.materials.size(), two.materials.size());
  for (std::size_t i = 0; i < one.materials.size(); ++i) {
    ASSERT_EQ(material_to_json(one.materials[i]), material_to_json(two.materials[i])) << i;
  }
  EXPECT_NE(one.spheres.center_x, other.spheres.center_x);
  // The cover's mix of materials: 80% diffuse, 15% metal, 5% glass (3 sigma of 30000 draws).
  std::size_t diffuse = 0, metal = 0;
  for (std::size_t i = 1; i <= 30000; ++i) {
    diffuse += std::holds_alternative<Lambertian>(one.materials[i]);
    metal += std::holds_alternative<Metal>(one.materials[i]);
  }
  EXPECT_NEAR(double(diffuse) / 30000, 0.80, 0.007);
  EXPECT_NEAR(double(metal) / 30000, 0.15, 0.006);
}

// A camera whose position is a float denormal, 5e-39 from spheres 3e-38 away (their sizes
// within float's normal range, as validate() asks): a render that flushed denormals to zero
// would see them from the origin. An application may have set its threads to flush them
// (Embree advises it); render() keeps IEEE's settings all the same, for its checks, its
// camera and its arenas, so the image is the one a default thread renders.
TEST(Render, DenormalsAreKeptWhateverTheCallersFloatingPointSettings) {
  Scene scene;
  scene.camera.lookfrom = {0, 0, 5e-39};
  scene.camera.lookat = {0, 0, -1e-38};
  scene.camera.vfov_degrees = 90;
  // A pinhole's film at distance 1 (at lookat, 1.5e-38 away, it would be below the smallest
  // focus distance rtiow accepts).
  scene.camera.focus_distance = 1.0;
  const std::uint32_t grey = scene.add_material(Lambertian{Color(0.5f, 0.5f, 0.5f)});
  scene.spheres.add({0, 0, -3e-38f}, 2e-38f, grey);
  scene.spheres.add({3e-38f, 0, -4e-38f}, 1.5e-38f, grey);
  RenderSettings settings = tiny(scene);
  settings.width = settings.height = 24;
  settings.threads = 2;
  settings.accel = AccelKind::Naive;
  const RenderResult ieee = render(scene, settings);
  const unsigned caller = _mm_getcsr();
  _mm_setcsr(caller | 0x8040);  // flush to zero, denormals are zero
  const RenderResult flushing = render(scene, settings);
  _mm_setcsr(caller);
  EXPECT_TRUE(test::bit_identical(ieee.film, flushing.film));
  // The spheres are there: the image's centre is darker than the sky's corner.
  const auto luminance = [&](int x, int y) {
    const Color c = ieee.film.at(x, y);
    return c.x + c.y + c.z;
  };
  EXPECT_LT(luminance(12, 12), 0.8f * luminance(0, 0));
  // And a sphere whose radius is a denormal is refused, not rendered as nothing by Embree.
  scene.spheres.radius[1] = 1e-39f;
  EXPECT_THROW(render(scene, settings), InvalidInput);
}

TEST(Render, RefusesInvalidSettingsBeforeWork) {
  const Scene scene = make_builtin_scene("materials", 1);
  RenderSettings settings = tiny(scene);
  settings.samples = FixedSamples{-1};  // (0 is the scene's count)
  EXPECT_THROW(render(scene, settings), InvalidInput);
  settings = tiny(scene);
  settings.width = -3;
  EXPECT_THROW(render(scene, settings), InvalidInput);
  settings = tiny(scene);
  settings.width = 100000;
  settings.height = 100000;
  EXPECT_THROW(render(scene, settings), InvalidInput);
}

}  // namespace
}  // namespace rtiow
