#pragma once
// How far a render is toward its end, in every mode: the share of its samples, its budget or
// its time spent, the time to go where an honest one exists, and for the error targets the
// error reached against the one asked. A pure function of a snapshot of the render's counters,
// so each mode's figures are tested without a render (the display only prints them).

#include <cstdint>
#include <string>

#include "core/render/render_settings.h"

namespace rtiow {

// Seconds until `total` samples are done at this run's rate: `done` of them are, `resumed` of
// those came from a checkpoint (they took none of the `elapsed` seconds). Negative when this
// run has done nothing yet, so there is no rate.
inline double seconds_to_go(std::uint64_t done, std::uint64_t resumed, std::uint64_t total,
                            double elapsed) {
  if (done <= resumed || done > total || elapsed <= 0.0) return -1.0;
  return double(total - done) * elapsed / double(done - resumed);
}

// The render's counters at one moment (RenderProgress's, read once).
struct ProgressSnapshot {
  std::uint64_t samples_done = 0, samples_resumed = 0, rays_traced = 0;
  double elapsed = 0.0;         // since the display began (the scene's build included)
  double loop_seconds = -1.0;   // this run's time in the sample loop; negative: not begun
  double seconds_before = 0.0;  // a resumed render's time before this run
  double image_error = -1.0;
  std::int64_t pixels_above_target = -1;
  double budget_rays = 0.0, spent_rays = 0.0;
  std::uint64_t rays_at_judgement = 0;
  double judging_seconds = 0.0;  // of elapsed, this run's in the denoiser's judgements
};

ProgressSnapshot snapshot(const RenderProgress& progress, double elapsed);

// The rate the rays are traced at, in millions a second: over the time less the judgements'.
double live_mrays_per_second(const ProgressSnapshot& now);

struct ProgressStatus {
  double fraction = -1.0;       // of the way to the render's end, 0 to 1; negative: unknown
  double seconds_to_go = -1.0;  // negative: none honest
  std::string detail;           // the error targets' figures: "error 0.031 (asked 0.02)"
};

ProgressStatus progress_status(const RenderSettings& settings, std::uint64_t pixels,
                               const ProgressSnapshot& now);

}  // namespace rtiow
