#pragma once
// What a render is asked for (RenderSettings), what it reports while it runs (RenderProgress)
// and what it returns (RenderResult): the types, apart from the entry point (render.h), so the
// code that only describes, stores or checks a render needs nothing of how it is done.

#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/film/film.h"
#include "core/film/pixel_sums.h"
#include "core/render/first_hit_passes.h"
#include "core/render/sample_budget.h"
#include "core/sampling/sampler.h"

namespace rtiow {

struct DenoisedImage;  // core/denoise/denoiser.h

enum class AccelKind { Embree, Naive };

// A region of the frame, in pixels: columns [x0, x1) and rows [y0, y1), row 0 at the top.
struct PixelRegion {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  bool operator==(const PixelRegion&) const = default;
};

// As --crop and the metadata write it: "X0,Y0,X1,Y1".
std::string to_string(const PixelRegion& region);

std::string to_string(AccelKind kind);
AccelKind parse_accel(const std::string& name);  // throws InvalidInput

// RenderSettings::max_depth that is the scene's (ImageSettings::max_depth): 0 is a depth, so
// "the scene's" needs a value of its own.
inline constexpr int kSceneDepth = -1;

struct RenderSettings {
  // 0: the scene's image (ImageSettings), as a scene file and the command line take it: the
  // side not given follows from the other and the scene's aspect ratio.
  int width = 0;
  int height = 0;
  // Render only this region of the width x height frame: the film holds the region's pixels,
  // each the same bits the whole frame's render gives it (uniform sampling only: an adaptive
  // pixel's samples depend on pixels outside any region).
  std::optional<PixelRegion> crop;
  // How many samples per pixel and what ends the render (core/render/sample_budget.h); a
  // count of 0 is the scene's samples_per_pixel...
  SampleBudget samples = FixedSamples{0};
  std::uint64_t first_sample = 0;  // ...starting at this sample index (a share of a render)
  int max_depth = kSceneDepth;     // the most rays a path takes; kSceneDepth: the scene's
  std::uint64_t seed = 1;
  int threads = 0;                  // 0: all cores
  double time_limit_seconds = 0.0;  // > 0: stop after the pass that reaches this much time
  AccelKind accel = AccelKind::Embree;
  // Sobol: at equal time 2.3-5.4x lower relMSE than independent sampling on every built-in
  // scene (docs/accuracy.md); the book's sampler is Independent.
  SamplerKind sampler = SamplerKind::Sobol;
  // Keep what an estimate of each pixel's error needs: two independent replicates of the
  // sampler's sequence (core/sampling/sampler.h). The variance channels ask for it; the error
  // targets always have it. Without it a render draws one sequence, and its image is less noisy.
  bool estimate_error = false;
  // Russian roulette by throughput (core/render/russian_roulette.h): 7% less time on the cover
  // for 1% more squared error. Off, every path runs to max_depth as in the book's program: the
  // book's own estimator, for comparisons with it ray for ray. The expected image is the same.
  bool russian_roulette = true;
  // The first hit's albedo, normal and depth, each the mean over the pixel's samples
  // (core/render/first_hit_passes.h): kept as exact sums beside the image's when any is asked.
  FirstHitPasses passes;
};

// RenderSettings::russian_roulette as --roulette and the provenance spell it.
inline std::string roulette_name(bool russian_roulette) {
  return russian_roulette ? "on" : "off";
}

// The film's size: the crop's, or the frame's.
inline int film_width(const RenderSettings& s) {
  return s.crop ? s.crop->width() : s.width;
}
inline int film_height(const RenderSettings& s) {
  return s.crop ? s.crop->height() : s.height;
}

// Where the film lies in the frame: a crop's place, or the whole frame.
inline FramePlacement frame_placement(const RenderSettings& s) {
  if (!s.crop) return {};
  return {s.crop->x0, s.crop->y0, s.width, s.height};
}

// Whether pixels get different sample counts (any adaptive mode).
inline bool is_adaptive(const RenderSettings& s) {
  return is_adaptive(s.samples);
}

// How many independent replicates a pixel's samples alternate between: kReplicates where the
// render estimates its error (or the sampler's samples are independent anyway), else 1. An
// adaptive budget (--adaptive) draws one sequence: it only compares pixels with one another to
// share its samples out, for which one sequence's sample variance serves (docs/accuracy.md);
// an error target (--image-error, --target-error) needs the calibrated error of two.
inline int replicates(const RenderSettings& s) {
  const bool error_target = is_adaptive(s) && !std::holds_alternative<AdaptiveBudget>(s.samples);
  return s.estimate_error || error_target || s.sampler == SamplerKind::Independent ? kReplicates
                                                                                   : 1;
}

// The pixel samples a uniform render takes in all (width x height x spp): what a progress
// display counts toward; none where that is not known in advance (adaptive sampling, a bare
// time limit).
inline std::optional<std::uint64_t> uniform_total_samples(const RenderSettings& s) {
  const auto* fixed = std::get_if<FixedSamples>(&s.samples);
  if (!fixed) return std::nullopt;
  return std::uint64_t(film_width(s)) * std::uint64_t(film_height(s)) *
         std::uint64_t(fixed->per_pixel);
}

// Throws InvalidInput naming the setting: non-positive size or spp, negative depth,
// an image too large to hold in memory, negative threads, a bad target error.
void validate(const RenderSettings& settings);

// Shared with other threads while the render runs: counters it updates (for a progress
// display) and a request to stop that it honours at the end of the current pass.
struct RenderProgress {
  std::atomic<std::uint64_t> samples_done{0};  // pixel samples, over all pixels
  // Of samples_done, those a resumed render started with (from its checkpoint): the rate of
  // this run's work, and so its time to go, leaves them out.
  std::atomic<std::uint64_t> samples_resumed{0};
  std::atomic<std::uint64_t> rays_traced{0};  // by this run
  std::atomic<bool> stop_requested{false};
  // Why whoever sets stop_requested would set it, in the words the summary and the image's
  // metadata record (RenderResult::stop_cause); set before the render starts.
  std::string stop_cause = "stopped on request";
  // What the time limit counts: when this run's sample loop began (steady clock, ns since its
  // epoch; 0: not yet), and the seconds a resumed render's checkpoint had spent before.
  std::atomic<std::int64_t> loop_start_ns{0};
  std::atomic<double> seconds_before{0.0};
  // What the adaptive modes publish each time a round is judged (`judgements` counts them):
  // --image-error's estimated error; --target-error's pixels still above the target;
  // --adaptive's budget and the cost spent, in rays, with this run's rays_traced then.
  std::atomic<std::uint32_t> judgements{0};
  std::atomic<double> image_error{-1.0};
  std::atomic<std::int64_t> pixels_above_target{-1};
  std::atomic<double> budget_rays{0.0};
  std::atomic<double> spent_rays{0.0};
  std::atomic<std::uint64_t> rays_at_judgement{0};
  // --image-error with --denoise: this run's seconds in the denoiser's finished judgements, and
  // when the one under way began (steady clock, ns since its epoch; 0: none), so that the live
  // rate leaves them out as the summary's does.
  std::atomic<double> judging_seconds{0.0};
  std::atomic<std::int64_t> judging_since_ns{0};
};

// What a render's estimated image error is worth. Calibrated: from two independent replicates
// (or independent samples), within a few percent of the true error (docs/accuracy.md). Upper
// bound: one Sobol sequence, whose sample variance overstates its mean's error (1.3-1.6x on the
// cover at 16-64 spp, more at higher counts, where the sequence gains more). None: a pixel with
// fewer than two samples, or a denoised error target's render ended before a judgement of its
// final sums (until the image denoised for its output gives one: take_delivered_estimate()).
enum class ErrorEstimate { None, Calibrated, UpperBound };

struct RenderResult {
  Film film;  // the mean of the samples completed
  // Their exact sums, for merging shares of a render: the colour's, the spreads for each
  // pixel's variance, and with passes asked what the passes are the mean of.
  PixelSums sums;
  std::vector<std::uint32_t> pixel_samples;        // each pixel's sample count
  std::vector<std::uint64_t> pixel_rays;           // the rays each pixel's samples traced
  std::vector<std::uint32_t> targets;              // adaptive: the round's targets (a state's)
  bool last_round = false;                         // adaptive: the round under way is the last
  std::uint64_t first_sample = 0;                  // each pixel's samples start at this index
  SamplerKind sampler = SamplerKind::Independent;  // what drew them
  int replicates = kReplicates;                    // in how many independent sequences
  int samples_completed = 0;    // per pixel (the most any pixel took when adaptive)
  bool stopped = false;         // a stop request ended the render early...
  std::string stop_cause;       // ...for this reason (RenderProgress::stop_cause)
  bool time_limited = false;    // the time limit ended it (with the samples completed)
  double build_seconds = 0.0;   // accelerator construction
  double render_seconds = 0.0;  // the sample loop
  // Of render_seconds, the denoiser's judgements between rounds (--image-error with --denoise).
  double judging_seconds = 0.0;
  std::uint64_t rays_traced = 0;
  // The image's estimated relative RMS error (offset 0.01), what it is worth, and
  // --target-error's count of pixels still above the target: at the --spp cap, or where a time
  // limit or a stop ended it, all of them. --image-error's
  // is its last judgement's where that judged the finished sums, and where the render ended
  // between judgements (a time limit, a stop) that of the finished sums: the pooled estimate's,
  // or with --denoise none (0) until the image denoised for the output gives it
  // (take_delivered_estimate()); every other render's is taken from its finished sums.
  double estimated_image_error = 0.0;
  ErrorEstimate error_estimate = ErrorEstimate::None;
  std::uint64_t pixels_above_target = 0;
  // --image-error with --denoise: the denoiser's image of these very sums, made by the last
  // judgement (not made again to be written); empty where the render ended otherwise.
  std::shared_ptr<const DenoisedImage> denoised;
  // Each pixel's ratio of honest to sample variance (core/film/replicate_variance.h) as the
  // image's error estimate took it from these very sums, for --stats-channels' variances to
  // take too (it costs a third of a second a megapixel); empty where no estimate made it or
  // RenderSettings::estimate_error did not ask for the pixels' variances.
  std::shared_ptr<const std::vector<Vec3d>> replicate_ratios;
};

// `rays` over `seconds`, in millions a second (0 without time): the one formula of every rate
// rtiow reports.
inline double mrays_per_second(double rays, double seconds) {
  return seconds > 0 ? rays / seconds * 1e-6 : 0.0;
}

// The rate the render traced its rays at: over its time less its judgements' (a denoised error
// target spends as long denoising between rounds as tracing).
inline double tracing_mrays_per_second(const RenderResult& r) {
  return mrays_per_second(double(r.rays_traced), r.render_seconds - r.judging_seconds);
}

}  // namespace rtiow
