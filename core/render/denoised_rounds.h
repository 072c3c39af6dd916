#pragma once
// --image-error E with --denoise: rounds judged by the denoised image's own estimated error
// (core/denoise/denoiser.h), not the noisy image's. Every pixel takes the same count: the
// denoiser compares each pixel's two halves and was calibrated on uniform renders
// (docs/denoising.md). After each round the denoiser runs on the sums as they stand; the render
// ends where its estimate is at most kImageErrorAim E, or else every pixel goes to the count
// next_denoised_count() gives. The next count is a function of the state alone, so a render
// resumed from a save is judged as the uninterrupted one was, and the image is the one
// `--spp N --denoise` gives at the count it ends at.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>

#include "core/denoise/denoiser.h"
#include "core/render/adaptive_sampling.h"
#include "core/render/denoised_output.h"

namespace rtiow {

// The count a denoised image of `error` at n spp needs to reach `aim`, if its error falls as
// n^-1/2 (a noisy mean's rate; a denoised image's falls no faster, so the guess errs short and
// costs another look rather than samples): at least n 2^(1/4), at most 4n and `most`.
inline std::uint32_t next_denoised_count(std::uint32_t n, double error, double aim,
                                         std::uint32_t most) {
  const double reaches = std::ceil(double(n) * (error / aim) * (error / aim));
  const double least_step = std::ceil(double(n) * 1.189207115002721);  // 2^(1/4)
  const double next = std::max(least_step, std::min(4.0 * double(n), reaches));
  return std::uint32_t(std::min(double(most), next));
}

// The denoiser's image of the state's sums; throws DenoiseCancelled once `cancelled` is true.
// (No progress of its own: the render's display shows the rounds' error.)
inline DenoisedImage denoise_state(const RenderSettings& settings, const PixelAccumulators& pixels,
                                   const std::function<bool()>& cancelled) {
  return denoise(
      denoise_input(DenoiseSource{pixels.sums, pixels.samples, settings.first_sample,
                                  replicates(settings), settings.width, settings.height}),
      DenoiseControl{cancelled});
}

template <typename Accel>
void render_by_denoised_error(const RenderContext<Accel>& ctx, const ImageErrorTarget& target,
                              RenderProgress* progress, RenderJournal& journal,
                              RenderResult& result) {
  RenderState& state = journal.state();
  RoundDeadline deadline(ctx.settings, progress, journal);
  const auto [least, most] = count_range(target);
  const double aim = kImageErrorAim * target.error;
  for (bool first = start_rounds(state, least);; first = false) {
    render_round(ctx, first, deadline, journal, progress, result);
    if (deadline.ended()) break;
    // A stop or the time limit ends the judgement too (a large image's takes seconds): the
    // render ends as one stopped in a round does, judged by its last finished judgement.
    std::shared_ptr<const DenoisedImage> denoised;
    const auto judging = Clock::now();
    progress->judging_since_ns =
        std::chrono::duration_cast<std::chrono::nanoseconds>(judging.time_since_epoch()).count();
    // This run's judging, for the live rate; the result's counts the runs before too.
    const auto judged = [&] {
      const double seconds = seconds_since(judging);
      result.judging_seconds += seconds;
      progress->judging_seconds = progress->judging_seconds + seconds;
      progress->judging_since_ns = 0;
    };
    try {
      denoised = std::make_shared<const DenoisedImage>(with_threads(ctx.settings.threads, [&] {
        return denoise_state(ctx.settings, state.pixels, [&] { return deadline(); });
      }));
    } catch (const DenoiseCancelled&) {
      judged();
      break;
    }
    judged();
    result.estimated_image_error = denoised->estimated_error;
    progress->image_error = result.estimated_image_error;
    ++progress->judgements;
    const std::uint32_t n = state.pixels.samples.front();  // every pixel's
    const std::uint32_t next = next_denoised_count(n, denoised->estimated_error, aim, most);
    if (denoised->estimated_error <= aim || n >= most) {
      result.denoised = std::move(denoised);  // the image of the sums the render ends with
      break;
    }
    std::fill(state.targets.begin(), state.targets.end(), next);
  }
  // Ended between judgements (its time limit, a stop): no judgement saw the sums the image is
  // made of, so the render has no estimate of its own; the image denoised for the output carries
  // one (take_delivered_estimate() in core/render/denoised_output.h).
  if (deadline.ended()) result.estimated_image_error = 0.0;
  deadline.report(result, state.pixels);
}

}  // namespace rtiow
