#include "core/session/session_report.h"

#include <cstdio>
#include <optional>

#include "core/limits/error.h"
#include "core/limits/setting_name.h"
#include "core/render/render_outcome.h"

namespace rtiow {

std::string long_request_note(const RenderSettings& s) {
  const std::optional<std::uint64_t> total = uniform_total_samples(s);
  if (!total || s.time_limit_seconds > 0) return "";
  const double samples = double(*total);
  constexpr double kSamplesPerSecond = 5e6, kDay = 86400;
  const double days = samples / kSamplesPerSecond / kDay;
  if (days < 1) return "";
  char text[160];
  std::snprintf(text, sizeof text,
                "%d spp at %dx%d is %.3g samples, about %.3g days on a 2-core machine; ",
                *spp_option(s.samples), film_width(s), film_height(s), samples, days);
  return text + ("a signal (Ctrl-C) keeps what is done and " + setting("resume") +
                 " continues it, " + setting("time_limit") + " bounds it");
}

std::string stopped_render_report(const RenderJob& job, const RenderResult& result,
                                  const CheckpointSession* checkpoint, const SessionEnd& end) {
  const RenderOutcome outcome = describe_outcome(job.settings, result);
  const std::string continued = checkpoint && checkpoint->holds_the_render()
                                    ? quote_value(checkpoint->kept_at(), kWholePath) + " (" +
                                          checkpoint->how_to_continue() + " to continue it)"
                                    : "";
  const std::string untouched = end.left_alone.empty()
                                    ? ""
                                    : "; " + quote_value(end.left_alone, kWholePath) +
                                          ", which this render did not finish, is left as it was";
  if (end.kept_in_checkpoint) {
    return outcome.samples + outcome.asked + " kept in " + continued + untouched;
  }
  return "wrote " + outcome.samples + outcome.asked + " to " + one_line(end.written) +
         (continued.empty() ? "" : "; the render is kept in " + continued) + untouched;
}

}  // namespace rtiow
