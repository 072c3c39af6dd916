#pragma once
// One render: a scene, settings and a seed in, a film out. The result is a pure function
// of (scene, settings without `threads`, seed): identical for any thread count and for
// either accelerator.

#include <atomic>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/film/film.h"
#include "core/film/pixel_variance.h"
#include "core/film/sample_sum.h"
#include "core/render/sample_budget.h"
#include "core/sampling/sampler.h"
#include "core/scene/scene.h"

namespace rtiow {

enum class AccelKind { Embree, Naive };

std::string to_string(AccelKind kind);
AccelKind parse_accel(const std::string& name);  // throws InvalidInput

struct RenderSettings {
  int width = 0;
  int height = 0;
  // How many samples per pixel and what ends the render (core/render/sample_budget.h)...
  SampleBudget samples = FixedSamples{1};
  std::uint64_t first_sample = 0;  // ...starting at this sample index (a share of a render)
  int max_depth = 50;
  std::uint64_t seed = 1;
  int threads = 0;                  // 0: all cores
  double time_limit_seconds = 0.0;  // > 0: stop after the pass that reaches this much time
  AccelKind accel = AccelKind::Embree;
  // Sobol: at equal time 2.3-5.4x lower relMSE than independent sampling on every built-in
  // scene (docs/accuracy.md); the book's sampler is Independent.
  SamplerKind sampler = SamplerKind::Sobol;
  // Keep what an estimate of each pixel's error needs: two independent replicates of the
  // sampler's sequence (core/sampling/sampler.h). The variance channels ask for it; the adaptive
  // modes always have it. Without it a render draws one sequence, and its image is less noisy.
  bool estimate_error = false;
};

// Whether pixels get different sample counts (any adaptive mode).
inline bool is_adaptive(const RenderSettings& s) {
  return is_adaptive(s.samples);
}

// How many independent replicates a pixel's samples alternate between: kReplicates where the
// render estimates its error (or the sampler's samples are independent anyway), else 1.
inline int replicates(const RenderSettings& s) {
  return s.estimate_error || is_adaptive(s) || s.sampler == SamplerKind::Independent ? kReplicates
                                                                                     : 1;
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
};

struct RenderResult {
  Film film;                                 // the mean of the samples completed
  std::vector<PixelSum> sums;                // their exact sums, for merging shares of a render
  std::vector<PixelSpread> spreads;          // for each pixel's variance
  std::vector<std::uint32_t> pixel_samples;  // each pixel's sample count
  std::vector<std::uint64_t> pixel_rays;     // the rays each pixel's samples traced
  std::vector<std::uint32_t> targets;        // adaptive: the round's targets (a state's)
  bool last_round = false;                   // adaptive: the round under way is the last
  std::uint64_t first_sample = 0;            // each pixel's samples start at this index
  SamplerKind sampler = SamplerKind::Independent;  // what drew them
  int replicates = kReplicates;                    // in how many independent sequences
  int samples_completed = 0;    // per pixel (the most any pixel took when adaptive)
  bool stopped = false;         // a stop request ended the render early
  bool time_limited = false;    // the time limit ended it (with the samples completed)
  double build_seconds = 0.0;   // accelerator construction
  double render_seconds = 0.0;  // the sample loop
  std::uint64_t rays_traced = 0;
  // Where the error-driven modes ended: --image-error's estimated relative RMS error of the
  // image, and --target-error's count of pixels still above the target at the --spp cap.
  double estimated_image_error = 0.0;
  std::uint64_t pixels_above_target = 0;
};

// Everything a render checks before any work: the settings, the scene, and that the camera
// rays of this image size are traceable. Throws InvalidInput.
void validate(const Scene& scene, const RenderSettings& settings);

struct Checkpointing;  // core/render/render_state.h
struct RenderState;

// The state a render ended in, copied back out of its result: for a caller that keeps it after
// the render (in a checkpoint, when the image could not be written).
RenderState state_of(const RenderResult& result);

// Validates the scene's camera and the settings (throwing InvalidInput before any work),
// builds the accelerator and renders in passes: each pass adds a few samples to every
// pixel, and the pixel sums continue across passes in sample order, so the image does not
// depend on how samples were grouped into passes. With `checkpointing`, the render starts
// from a saved state and saves its own as it goes: continued, it gives the same bits.
RenderResult render(const Scene& scene, const RenderSettings& settings,
                    RenderProgress* progress = nullptr,
                    const Checkpointing* checkpointing = nullptr);

// Starts oneTBB now rather than at the render's first pass. oneTBB dlopens its allocator on
// first use, and a dlopen waits for any other under way: a program that loads a library on
// another thread during the render (the image backend) calls this first, or the render
// waits for that whole load.
void start_parallel_runtime();

}  // namespace rtiow
