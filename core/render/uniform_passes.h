#pragma once
// Uniform sampling: every pixel gets the same samples, in passes of about a second, so that
// a stop request or a time limit is honoured soon. Grouping never changes the image.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <variant>

#include "core/render/render_loop.h"
#include "core/render/render_state.h"
#include "core/render/stopwatch.h"

namespace rtiow {

// How many samples the next pass takes: about a second's worth, judged from the last pass,
// so a stop request is honoured soon. (Grouping never changes the image.)
inline std::uint64_t next_pass_samples(std::uint64_t last_pass, double last_seconds,
                                       std::uint64_t remaining) {
  constexpr double kTargetSeconds = 1.0;
  double n = double(last_pass) * (last_seconds > 0 ? kTargetSeconds / last_seconds : 4.0);
  n = std::clamp(n, 1.0, 4.0 * double(last_pass));
  return std::min(remaining, std::uint64_t(n));
}

// Every pixel gets the same samples, in passes of about a second, continuing from the
// journal's state (all its pixels have the same count) and saving it between passes when due.
template <typename Accel>
void render_uniform(const RenderContext<Accel>& ctx, RenderProgress* progress,
                    RenderJournal& journal, RenderResult& result) {
  const RenderSettings& settings = ctx.settings;
  PixelAccumulators& pixels = journal.state().pixels;
  // Until the time limit, passes may go on to the most an int count holds.
  const auto* fixed = std::get_if<FixedSamples>(&settings.samples);
  const auto total = std::uint64_t(fixed ? fixed->per_pixel : std::numeric_limits<int>::max());
  const double limit = settings.time_limit_seconds;
  std::uint64_t done = pixels.samples.empty() ? 0 : pixels.samples[0], pass = 1;
  while (done < total) {
    if (done > 0 && progress->stop_requested.load()) {
      result.stopped = true;
      result.stop_cause = progress->stop_cause;
      break;
    }
    if (done > 0 && limit > 0.0 && journal.elapsed() >= limit) {  // spent before a resume
      result.time_limited = true;
      break;
    }
    const auto pass_start = Clock::now();
    result.rays_traced += render_pass(ctx, std::uint32_t(done + pass), pixels, progress);
    done += pass;
    const double pass_seconds = seconds_since(pass_start);
    if (journal.due()) journal.save(result);
    const double seconds_per_sample = pass_seconds / double(pass);
    pass = next_pass_samples(pass, pass_seconds, total - done);
    if (limit > 0.0 && done < total) {
      // End within one pass of the limit: stop once it is reached, and size the next pass to
      // what the remaining time holds at the rate just measured.
      const double left = limit - journal.elapsed();
      if (left <= 0.0) {
        result.time_limited = true;
        break;
      }
      const double fits = left / std::max(seconds_per_sample, 1e-9);
      pass = std::clamp<std::uint64_t>(std::uint64_t(fits), 1, pass);
    }
  }
  result.samples_completed = int(done);
}

}  // namespace rtiow
