#include "core/render/render.h"

#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <variant>

#include "core/accel/embree_accel.h"
#include "core/accel/naive_accel.h"
#include "core/io/input_file.h"
#include "core/limits/error.h"
#include "core/limits/image_size.h"
#include "core/limits/input_limits.h"
#include "core/limits/nearest_name.h"
#include "core/limits/setting_name.h"
#include "core/parallel/ieee_floating_point.h"
#include "core/parallel/thread_count.h"
#include "core/render/adaptive_sampling.h"
#include "core/render/denoised_rounds.h"
#include "core/render/render_loop.h"
#include "core/render/render_state.h"
#include "core/render/render_statistics.h"
#include "core/render/stopwatch.h"
#include "core/render/uniform_passes.h"
#include "core/scene/camera.h"

namespace rtiow {
namespace {

// A film costs this much per pixel: the float image and the exact fixed-point sums.
constexpr std::uint64_t kBytesPerPixel = sizeof(Color) + sizeof(PixelSum) + sizeof(PixelSpread) +
                                         sizeof(std::uint32_t) + sizeof(std::uint64_t);

// Each kind of budget's own ranges; the time limit is what ends an open-ended one. Worded for
// the library's names: the command line refuses its own mistakes first, in its words
// (core/render/render_request.cpp).
void validate_budget(const SampleBudget& budget, double time_limit_seconds) {
  const auto positive_spp = [](int spp) {
    if (spp <= 0) throw InvalidInput("spp must be > 0, got " + std::to_string(spp));
  };
  const auto finite_error = [](double error, const char* what) {
    if (!(error > 0.0) || !std::isfinite(error)) {
      throw InvalidInput(std::string(what) + " must be a finite number > 0");
    }
  };
  const auto valid_least = [](int least) {
    if (least < 2) {
      throw InvalidInput("minimum samples must be >= 2 (a variance needs two), got " +
                         std::to_string(least));
    }
  };
  const bool timed = time_limit_seconds > 0.0;
  if (const auto* f = std::get_if<FixedSamples>(&budget)) {
    positive_spp(f->per_pixel);
  } else if (std::holds_alternative<UntilTimeLimit>(budget)) {
    if (!timed) throw InvalidInput("a render until the time limit needs a time limit > 0");
  } else if (const auto* a = std::get_if<AdaptiveBudget>(&budget)) {
    valid_least(a->least);
    if (!a->per_pixel && !timed) {
      throw InvalidInput(
          "an AdaptiveBudget needs a budget: per_pixel, a time limit (time_limit_seconds) or "
          "both");
    }
    if (a->per_pixel) positive_spp(*a->per_pixel);
    // A budget no larger than the minimum leaves nothing to allocate: the render would be
    // uniform while its metadata says adaptive.
    if (a->per_pixel && *a->per_pixel <= a->least) {
      throw InvalidInput("AdaptiveBudget: per_pixel " + std::to_string(*a->per_pixel) +
                         " leaves nothing to allocate after every pixel's minimum (least) of " +
                         std::to_string(a->least) +
                         "; give per_pixel above it, or FixedSamples for a uniform render");
    }
  } else if (const auto* t = std::get_if<PixelErrorTarget>(&budget)) {
    finite_error(t->error, "target error");
    positive_spp(t->most);
    valid_least(t->least);
  } else if (const auto* i = std::get_if<ImageErrorTarget>(&budget)) {
    finite_error(i->error, "image error");
    positive_spp(i->most);
    valid_least(i->least);
  }
}

// A resumed state must be of this render's size and, for uniform sampling, hold one count
// no larger than the one asked (the checkpoint's identity was checked by whoever read it).
void check_resumable(const RenderState& state, const RenderSettings& settings) {
  const std::uint64_t pixels = std::uint64_t(settings.width) * std::uint64_t(settings.height);
  const PixelAccumulators& p = state.pixels;
  if (p.sums.size() != pixels || p.sums.spreads.size() != pixels || p.samples.size() != pixels ||
      p.rays.size() != pixels || (!state.targets.empty() && state.targets.size() != pixels) ||
      p.sums.first_hits.size() != (settings.passes.any() ? pixels : 0)) {
    throw InvalidInput("the state to resume is not of a " + std::to_string(settings.width) + "x" +
                       std::to_string(settings.height) + " image" +
                       (settings.passes.any() ? " with passes" : " without passes"));
  }
  if (is_adaptive(settings)) return;
  const auto [least, most] = std::minmax_element(p.samples.begin(), p.samples.end());
  if (*least != *most) throw InvalidInput("the state to resume is not of a uniform render");
  const auto* fixed = std::get_if<FixedSamples>(&settings.samples);
  if (fixed && *most > std::uint32_t(fixed->per_pixel)) {
    throw InvalidInput("the render to resume already has " + std::to_string(*most) +
                       " spp, more than the " + std::to_string(fixed->per_pixel) + " asked: give " +
                       setting("spp", std::to_string(*most)) + " or more");
  }
}

// A crop's region inside the frame, and a mode that renders a region as the frame would.
void validate_crop(const RenderSettings& s) {
  if (!s.crop) return;
  const PixelRegion& c = *s.crop;
  if (c.x0 < 0 || c.y0 < 0 || c.x1 > s.width || c.y1 > s.height || c.x0 >= c.x1 || c.y0 >= c.y1) {
    throw InvalidInput("crop " + to_string(c) + " is not a region of the " +
                       std::to_string(s.width) + "x" + std::to_string(s.height) +
                       " image (X0,Y0,X1,Y1 in pixels from its top left, X1 and Y1 excluded: "
                       "0 <= X0 < X1 <= width, 0 <= Y0 < Y1 <= height)");
  }
  const auto* image = std::get_if<ImageErrorTarget>(&s.samples);
  if (image && image->denoised) {
    throw InvalidInput(
        "a crop renders a region as the frame would, but a denoised image error target would "
        "judge the region's error alone: render the frame, or give the region a sample count");
  }
  if (is_adaptive(s)) {
    throw InvalidInput(
        "a crop renders a region with uniform sampling only: adaptive sampling shares samples out "
        "by each pixel's neighbours and the whole image, so a region would get other pixels than "
        "the whole image has there");
  }
}

// The settings the sample loop works with: the film's size (a crop's), and where it lies in
// the frame.
RenderSettings film_settings(RenderSettings settings) {
  if (settings.crop) {
    settings.width = settings.crop->width();
    settings.height = settings.crop->height();
    settings.crop.reset();
  }
  return settings;
}

// The sample loop the budget asks for.
template <typename Accel>
void render_samples(const RenderContext<Accel>& ctx, RenderProgress* progress,
                    RenderJournal& journal, RenderResult& result) {
  const SampleBudget& samples = ctx.settings.samples;
  if (const auto* target = std::get_if<PixelErrorTarget>(&samples)) {
    render_adaptive(ctx, *target, progress, journal, result);
  } else if (const auto* image = std::get_if<ImageErrorTarget>(&samples);
             image && image->denoised) {
    render_by_denoised_error(ctx, *image, progress, journal, result);
  } else if (is_adaptive(samples)) {
    render_by_image_error(ctx, progress, journal, result);
  } else {
    render_uniform(ctx, progress, journal, result);
  }
}

template <typename Accel>
RenderResult render_with(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         const FramePlacement& frame, RenderProgress* progress,
                         const Checkpointing* checkpointing) {
  RenderProgress unobserved;
  if (!progress) progress = &unobserved;
  RenderResult result;
  const auto build_start = Clock::now();
  const Accel accel(scene.spheres);
  result.build_seconds = seconds_since(build_start);
  const RenderContext<Accel> ctx{scene, camera, accel, settings, frame};

  const std::size_t n = std::size_t(settings.width) * std::size_t(settings.height);
  RenderState state = checkpointing && checkpointing->resume
                          ? std::move(*checkpointing->resume)
                          : RenderState(n, settings.passes.any());
  result.rays_traced = state.rays_traced;
  result.judging_seconds = state.judging_seconds;
  result.estimated_image_error = state.estimated_image_error;
  result.pixels_above_target = state.pixels_above_target;
  std::uint64_t resumed = 0;
  for (const std::uint32_t s : state.pixels.samples) resumed += s;
  progress->samples_resumed = resumed;
  progress->samples_done += resumed;
  RenderJournal journal(state, checkpointing);
  progress->seconds_before = journal.elapsed();
  progress->loop_start_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                std::chrono::steady_clock::now().time_since_epoch())
                                .count();
  render_samples(ctx, progress, journal, result);
  result.render_seconds = journal.elapsed();
  journal.save(result, result.stopped ? SaveReason::Stopped : SaveReason::Finished);
  PixelAccumulators& pixels = state.pixels;
  result.film = Film(settings.width, settings.height);
  resolve(pixels.sums.color, pixels.samples, result.film);
  result.sums = std::move(pixels.sums);
  result.pixel_samples = std::move(pixels.samples);
  result.pixel_rays = std::move(pixels.rays);
  result.targets = std::move(state.targets);
  result.last_round = state.last_round;
  result.first_sample = settings.first_sample;
  result.sampler = settings.sampler;
  result.replicates = replicates(settings);
  if (std::holds_alternative<ImageErrorTarget>(settings.samples)) {
    // Its estimate of the finished sums (its last judgement's, or made as the render ended).
    const bool judged =
        result.estimated_image_error > 0.0 || !(result.stopped || result.time_limited);
    result.error_estimate = judged ? ErrorEstimate::Calibrated : ErrorEstimate::None;
  } else {
    const ImageErrorEstimate estimate = estimate_image_error(result, settings.threads);
    result.estimated_image_error = estimate.error;
    result.error_estimate = estimate.kind;
    // Kept where each pixel's variance is asked for (24 bytes a pixel, else dropped here).
    if (settings.estimate_error) result.replicate_ratios = estimate.replicate_ratios;
  }
  return result;
}

// What a film pixel and its accumulators take.
std::uint64_t film_bytes_per_pixel(const RenderSettings& s) {
  return kBytesPerPixel + (s.passes.any() ? sizeof(FirstHitSum) + 7 * sizeof(float) : 0);
}

}  // namespace

std::string to_string(const PixelRegion& region) {
  return std::to_string(region.x0) + "," + std::to_string(region.y0) + "," +
         std::to_string(region.x1) + "," + std::to_string(region.y1);
}

std::string to_string(AccelKind kind) {
  return kind == AccelKind::Embree ? EmbreeAccel::name() : NaiveAccel::name();
}

AccelKind parse_accel(const std::string& name) {
  if (name == EmbreeAccel::name()) return AccelKind::Embree;
  if (name == NaiveAccel::name()) return AccelKind::Naive;
  throw InvalidInput("unknown accelerator " + quote_value(name) +
                     did_you_mean(name, {EmbreeAccel::name(), NaiveAccel::name()}) +
                     " (known: embree, naive)");
}

void validate(const RenderSettings& s) {
  // Refuse before allocating what the machine cannot hold: the film and its accumulators, which
  // are a crop's region alone (issue 69: a 16x16 crop of a frame too large to hold renders, so
  // crops tile any frame rtiow accepts). The frame's sides and pixel count are bounded still:
  // its pixels key the samples.
  check_image_size(s.width, s.height, s.crop ? 0 : film_bytes_per_pixel(s));
  validate_budget(s.samples, s.time_limit_seconds);
  if (s.max_depth < 0 || s.max_depth > limits::kMaxDepth) {
    throw InvalidInput("depth must be from 0 to " + std::to_string(limits::kMaxDepth) + ", got " +
                       std::to_string(s.max_depth));
  }
  check_thread_count(s.threads);
  if (!(s.time_limit_seconds >= 0.0) || !std::isfinite(s.time_limit_seconds)) {
    throw InvalidInput("time limit must be a finite number of seconds >= 0");
  }
  const auto* fixed = std::get_if<FixedSamples>(&s.samples);
  const std::uint64_t last = s.first_sample + std::uint64_t(fixed ? fixed->per_pixel : 0);
  if (s.first_sample > limits::kMaxSampleIndex || last > limits::kMaxSampleIndex) {
    throw InvalidInput("samples " + std::to_string(s.first_sample) + " to " + std::to_string(last) +
                       " go beyond sample index 2^32");
  }
  if (s.first_sample > 0 && !fixed) {
    throw InvalidInput("a share of a render (its first sample above 0) has a fixed sample count");
  }
  validate_crop(s);
  if (s.crop) check_image_size(film_width(s), film_height(s), film_bytes_per_pixel(s));
  const auto* image = std::get_if<ImageErrorTarget>(&s.samples);
  if (image && image->denoised &&
      (replicates(s) != kReplicates || !(s.passes.albedo && s.passes.normal && s.passes.depth))) {
    throw InvalidInput(
        "an ImageErrorTarget of the denoised image needs what the denoiser reads: "
        "estimate_error (two independent halves) and the albedo, normal and depth passes");
  }
}

void validate(const Scene& scene, const RenderSettings& settings) {
  validate(settings);
  validate(scene);
  validate(scene.camera, settings.width, settings.height);
}

RenderSettings with_scene_image(const Scene& scene, RenderSettings settings) {
  const ImageSettings& image = scene.image;
  // A side derived beyond an int's range stays 0, which validation then names.
  const auto side = [](double value) {
    return value >= 1.0 && value <= double(limits::kMaxImageSide) ? int(value) : 0;
  };
  if (settings.width == 0 && settings.height == 0) settings.width = image.width;
  if (settings.height == 0 && settings.width > 0) {
    settings.height = side(height_for_width(settings.width, image.aspect_ratio));
  } else if (settings.width == 0 && settings.height > 0) {
    settings.width = side(width_for_height(settings.height, image.aspect_ratio));
  }
  if (auto* fixed = std::get_if<FixedSamples>(&settings.samples); fixed && fixed->per_pixel == 0) {
    fixed->per_pixel = image.samples_per_pixel;
  }
  if (settings.max_depth == kSceneDepth) settings.max_depth = image.max_depth;
  return settings;
}

RenderResult render(const Scene& scene, const RenderSettings& asked, RenderProgress* progress,
                    const Checkpointing* checkpointing) {
  const IeeeFloatingPoint ieee;  // the checks and the camera too, whatever the caller's settings
  const RenderSettings settings = with_scene_image(scene, asked);
  validate(scene, settings);
  // The camera sees the whole frame; the sample loop fills the film (a crop of it).
  const Camera camera(scene.camera, settings.width, settings.height);
  const RenderSettings film = film_settings(settings);
  const FramePlacement frame = frame_placement(settings);
  if (checkpointing && checkpointing->resume) check_resumable(*checkpointing->resume, film);
  // The accelerator's build inside the render's thread count too.
  return with_threads(film.threads, [&] {
    return film.accel == AccelKind::Naive
               ? render_with<NaiveAccel>(scene, camera, film, frame, progress, checkpointing)
               : render_with<EmbreeAccel>(scene, camera, film, frame, progress, checkpointing);
  });
}

RenderState take_state(RenderResult& result) {
  RenderState state{0};
  state.pixels.sums = std::move(result.sums);
  state.pixels.samples = std::move(result.pixel_samples);
  state.pixels.rays = std::move(result.pixel_rays);
  state.targets = std::move(result.targets);
  state.last_round = result.last_round;
  state.rays_traced = result.rays_traced;
  state.render_seconds = result.render_seconds;
  state.judging_seconds = result.judging_seconds;
  state.estimated_image_error = result.estimated_image_error;
  state.pixels_above_target = result.pixels_above_target;
  return state;
}

void restore_state(RenderState&& state, RenderResult& result) {
  result.sums = std::move(state.pixels.sums);
  result.pixel_samples = std::move(state.pixels.samples);
  result.pixel_rays = std::move(state.pixels.rays);
  result.targets = std::move(state.targets);
}

void start_parallel_runtime() {
  tbb::task_arena arena;
  arena.initialize();
}

}  // namespace rtiow
