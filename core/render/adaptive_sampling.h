#pragma once
// Adaptive sampling (--target-error): pixels stop once their estimated relative standard
// error is below a target. The per-pixel spread itself is core/film/pixel_variance.h.

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/render/render_loop.h"
#include "core/render/stopwatch.h"

namespace rtiow {

// The relative variance per sample a pixel is judged by: the mean of its neighbours' in
// the 3x3 window around it, itself left out. A rule that looked at the pixel's own samples
// would stop more often after lucky ones (a bright sample lowers the relative error, a
// missed rare path the variance) and bias the pixel; its neighbours' samples are
// independent of its own, so its mean stays unbiased. A 1x1 image has no neighbours and
// uses its own.
std::vector<double> neighbourhood_relative_variance(const RenderSettings& settings,
                                                    const PixelAccumulators& pixels);

// Adaptive sampling: every pixel takes the minimum, then each round doubles the samples of
// the pixels whose estimated relative standard error is still above the target (up to the
// maximum). Decisions are made for all pixels before a round renders, from counts and sums
// that do not depend on timing, so the image is the same for any thread count. Few looks
// (one per doubling) and the neighbour-based estimate keep the stopping rule's bias small.
// A stop request or the time limit ends the render mid-round; untouched pixels keep their
// samples.
template <typename Accel>
void render_adaptive(const RenderContext<Accel>& ctx, RenderProgress* progress,
                     PixelAccumulators& pixels, RenderResult& result) {
  const RenderSettings& settings = ctx.settings;
  const auto render_start = Clock::now();
  const auto most = std::uint32_t(settings.samples_per_pixel);
  const auto least = std::min(most, std::uint32_t(settings.min_samples));
  const double target_variance = settings.target_error * settings.target_error;
  std::atomic<bool> stop_requested{false}, time_out{false};
  const std::function<bool()> may_skip = [&] {
    if (progress->stop_requested.load()) stop_requested = true;
    if (settings.time_limit_seconds > 0.0 &&
        seconds_since(render_start) >= settings.time_limit_seconds) {
      time_out = true;
    }
    return stop_requested.load() || time_out.load();
  };
  std::vector<std::uint32_t> targets(pixels.samples.size(), least);
  std::vector<std::size_t> list(pixels.samples.size());
  for (std::size_t p = 0; p < list.size(); ++p) list[p] = p;
  // The first round is never cut short: every pixel gets its minimum, so none is empty.
  const std::function<bool()> never = [] { return false; };
  for (bool first_round = true; !list.empty(); first_round = false) {
    result.rays_traced +=
        render_pixel_list(ctx, list, targets, pixels, progress, first_round ? never : may_skip);
    if (stop_requested || time_out) break;
    const std::vector<double> judged = neighbourhood_relative_variance(settings, pixels);
    list.clear();
    for (std::size_t p = 0; p < targets.size(); ++p) {
      const std::uint32_t n = pixels.samples[p];
      if (n >= most || judged[p] / double(n) <= target_variance) continue;
      targets[p] = std::min(most, 2 * n);
      list.push_back(p);
    }
  }
  result.stopped = stop_requested.load();
  result.time_limited = time_out.load() && !result.stopped;
  result.samples_completed = int(*std::max_element(pixels.samples.begin(), pixels.samples.end()));
}

}  // namespace rtiow
