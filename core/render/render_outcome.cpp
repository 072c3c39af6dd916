#include "core/render/render_outcome.h"

#include <algorithm>
#include <cstdio>
#include <variant>

#include "core/render/render_statistics.h"

namespace rtiow {
namespace {

// The adaptive goal and, for an error-driven render that ended short of it (at its cap, its
// time limit or a stop), how far it got: `most` the most samples a pixel took.
std::string adaptive_goal(const RenderSettings& s, const RenderResult& r, std::uint32_t most) {
  char goal[128] = "adaptive";
  if (const auto* t = std::get_if<PixelErrorTarget>(&s.samples)) {
    if (r.pixels_above_target > 0) {
      std::snprintf(goal, sizeof goal, "target error %g not reached by %llu pixels at %u spp",
                    t->error, static_cast<unsigned long long>(r.pixels_above_target), most);
    } else {
      std::snprintf(goal, sizeof goal, "target error %g", t->error);
    }
  }
  if (const auto* i = std::get_if<ImageErrorTarget>(&s.samples)) {
    const char* of = i->denoised ? "denoised image error" : "image error";
    if (!error_target_reached(s, r) && r.estimated_image_error == 0.0) {
      std::snprintf(goal, sizeof goal, "%s %g not reached: no estimate yet at %u spp", of, i->error,
                    most);
    } else if (!error_target_reached(s, r)) {
      std::snprintf(goal, sizeof goal, "%s %g not reached: %.3g at %u spp", of, i->error,
                    r.estimated_image_error, most);
    } else {
      std::snprintf(goal, sizeof goal, "%s %g", of, i->error);
    }
  }
  return goal;
}

std::string what_was_asked(const SampleBudget& b) {
  const std::optional<int> spp = spp_option(b);
  if (!spp) return {};
  const bool budget = std::holds_alternative<AdaptiveBudget>(b);
  const bool cap =
      std::holds_alternative<PixelErrorTarget>(b) || std::holds_alternative<ImageErrorTarget>(b);
  return (budget ? " (of a budget of "
          : cap  ? " (of a cap of "
                 : " (of ") +
         std::to_string(*spp) + (budget || cap ? " spp)" : " asked)");
}

}  // namespace

bool error_target_reached(const RenderSettings& s, const RenderResult& r) {
  if (std::holds_alternative<PixelErrorTarget>(s.samples)) return r.pixels_above_target == 0;
  if (const auto* i = std::get_if<ImageErrorTarget>(&s.samples)) {
    // A denoised target ended before a judgement of its final sums has no estimate until its
    // output's denoise gives one (0, which a finished render of a constant image also reports).
    const bool unjudged = (r.stopped || r.time_limited) && r.estimated_image_error == 0.0;
    return !unjudged && r.estimated_image_error <= i->error;
  }
  return true;
}

RenderOutcome describe_outcome(const RenderSettings& s, const RenderResult& r) {
  RenderOutcome o;
  char text[192];
  const auto* image = std::get_if<ImageErrorTarget>(&s.samples);
  if (is_adaptive(s.samples)) {
    const auto [least, most] = std::minmax_element(r.pixel_samples.begin(), r.pixel_samples.end());
    o.least = *least, o.most = *most, o.mean = mean_samples(r);
    if (image && image->denoised && o.least == o.most) {  // every pixel the same count
      std::snprintf(text, sizeof text, "%u spp (%s)", o.most, adaptive_goal(s, r, o.most).c_str());
    } else {
      std::snprintf(text, sizeof text, "%u-%u spp (mean %.1f, %s)", o.least, o.most, o.mean,
                    adaptive_goal(s, r, o.most).c_str());
    }
  } else {
    o.least = o.most = std::uint32_t(r.samples_completed), o.mean = r.samples_completed;
    std::snprintf(text, sizeof text, "%d spp", r.samples_completed);
  }
  o.samples = text;
  // --image-error's goal already holds its estimate.
  if (!std::holds_alternative<ImageErrorTarget>(s.samples)) o.error = describe_error_estimate(r);
  if (r.stopped) {
    o.asked = what_was_asked(s.samples);
    o.stopped = r.stop_cause.empty() ? "stopped on request" : r.stop_cause;
  } else if (r.time_limited) {
    std::snprintf(text, sizeof text, "time limit of %g s", s.time_limit_seconds);
    o.stopped = text;
  }
  return o;
}

}  // namespace rtiow
