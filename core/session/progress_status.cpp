#include "core/session/progress_status.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <variant>

namespace rtiow {
namespace {

// Picks the nearer end of two measures (samples or budget, and time): the larger share and
// the shorter time to go, each where known.
void take_nearer(ProgressStatus& status, double fraction, double to_go) {
  status.fraction = std::max(status.fraction, fraction);
  if (to_go >= 0.0 && (status.seconds_to_go < 0.0 || to_go < status.seconds_to_go)) {
    status.seconds_to_go = to_go;
  }
}

// A time limit: the share spent (with a resumed render's earlier time, as the limit counts
// it) and the rest, which the render ends within one pass of.
void add_time_limit(ProgressStatus& status, double limit, const ProgressSnapshot& now) {
  if (limit <= 0.0 || now.loop_seconds < 0.0) return;
  const double spent = now.seconds_before + now.loop_seconds;
  take_nearer(status, std::min(1.0, spent / limit), std::max(0.0, limit - spent));
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

}  // namespace

ProgressSnapshot snapshot(const RenderProgress& progress, double elapsed) {
  ProgressSnapshot s;
  s.samples_done = progress.samples_done, s.samples_resumed = progress.samples_resumed;
  s.rays_traced = progress.rays_traced, s.elapsed = elapsed;
  const std::int64_t now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                               std::chrono::steady_clock::now().time_since_epoch())
                               .count();
  if (const std::int64_t start = progress.loop_start_ns; start != 0)
    s.loop_seconds = double(now - start) * 1e-9;
  s.judging_seconds = progress.judging_seconds;
  if (const std::int64_t since = progress.judging_since_ns; since != 0)
    s.judging_seconds += double(now - since) * 1e-9;
  s.seconds_before = progress.seconds_before;
  s.image_error = progress.image_error, s.pixels_above_target = progress.pixels_above_target;
  s.budget_rays = progress.budget_rays, s.spent_rays = progress.spent_rays;
  s.rays_at_judgement = progress.rays_at_judgement;
  return s;
}

double live_mrays_per_second(const ProgressSnapshot& now) {
  return mrays_per_second(double(now.rays_traced), now.elapsed - now.judging_seconds);
}

ProgressStatus progress_status(const RenderSettings& settings, std::uint64_t pixels,
                               const ProgressSnapshot& now) {
  ProgressStatus status;
  const SampleBudget& budget = settings.samples;
  if (const auto* fixed = std::get_if<FixedSamples>(&budget)) {
    const std::uint64_t total = pixels * std::uint64_t(fixed->per_pixel);
    if (total > 0) {
      take_nearer(status, std::min(1.0, double(now.samples_done) / double(total)),
                  seconds_to_go(now.samples_done, now.samples_resumed, total, now.elapsed));
    }
  } else if (std::holds_alternative<AdaptiveBudget>(budget) && now.budget_rays > 0.0 &&
             std::isfinite(now.budget_rays)) {
    // The budget in rays, known once the first round is judged; the cost since then is
    // counted in rays as they are traced, and the rest goes at this run's rate.
    const double spent = now.spent_rays + double(now.rays_traced) - double(now.rays_at_judgement);
    const double rate = now.loop_seconds > 0.0 ? double(now.rays_traced) / now.loop_seconds : 0.0;
    const double left = std::max(0.0, now.budget_rays - spent);
    take_nearer(status, std::min(1.0, spent / now.budget_rays),
                rate > 0.0 && now.rays_traced > 0 ? left / rate : -1.0);
  } else if (const auto* image = std::get_if<ImageErrorTarget>(&budget)) {
    // No time to go: how fast the error falls is itself an estimate, round by round.
    status.detail = "error " + (now.image_error >= 0.0 ? number(now.image_error) : "?") +
                    " (asked " + number(image->error) + ")";
  } else if (const auto* pixel = std::get_if<PixelErrorTarget>(&budget)) {
    status.detail = (now.pixels_above_target >= 0 ? std::to_string(now.pixels_above_target) : "?") +
                    " of " + std::to_string(pixels) + " pixels above error " + number(pixel->error);
  }
  add_time_limit(status, settings.time_limit_seconds, now);
  return status;
}

}  // namespace rtiow
