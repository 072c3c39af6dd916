#include "core/session/progress_display.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "core/session/progress_status.h"

namespace rtiow {
namespace {

// "37.5%  elapsed 12.0s  ETA 20.0s  error 0.031 (asked 0.02)  14.2 Mrays/s"; a mode with no
// share of its end to show counts its samples instead, and one with no honest time to go
// shows none. A log's line says the share as it is when the line is written (it gave the tenth
// just passed: "90% ... ETA 0.1s").
std::string progress_line(const ProgressStatus& status, const ProgressSnapshot& now) {
  char text[64];
  std::string line;
  if (status.fraction >= 0.0) {
    std::snprintf(text, sizeof text, "%5.1f%%", 100.0 * status.fraction);
  } else {
    std::snprintf(text, sizeof text, "%.3g samples", double(now.samples_done));
  }
  line += text;
  line += "  elapsed " + duration_text(now.elapsed);
  if (status.fraction >= 0.0) {
    line += "  ETA " + (status.seconds_to_go >= 0.0 ? duration_text(status.seconds_to_go) : "?");
  }
  if (!status.detail.empty()) line += "  " + status.detail;
  std::snprintf(text, sizeof text, "  %.1f Mrays/s", live_mrays_per_second(now));
  return line + text;
}

}  // namespace

ProgressDisplay::ProgressDisplay(const RenderProgress& progress, const RenderSettings& settings)
    : progress_(progress),
      settings_(settings),
      pixels_(std::uint64_t(film_width(settings)) * std::uint64_t(film_height(settings))),
      terminal_(stderr_is_terminal()),
      start_(std::chrono::steady_clock::now()) {
  // Without a thread (a limit of processes) the render goes on without the live display, and
  // its final report is still printed.
  thread_.emplace(terminal_ ? std::chrono::milliseconds(250) : std::chrono::milliseconds(1000),
                  [this] { report(false); });
}

ProgressDisplay::~ProgressDisplay() {
  thread_.reset();
  report(true);
  if (terminal_) std::fputc('\n', stderr);
}

void ProgressDisplay::report(bool final_report) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const ProgressSnapshot now = snapshot(progress_, elapsed);
  const ProgressStatus status = progress_status(settings_, pixels_, now);
  if (terminal_) {
    draw_live_line(progress_line(status, now));
    return;
  }
  // Not a terminal: a line per tenth of the way (or, with no share to show, every ten seconds)
  // and per round judged, so a log stays short; none once a signal has asked the render to
  // stop (its "stopping" line is the last word until the summary).
  if (final_report || progress_.stop_requested) return;
  const int step = status.fraction >= 0.0 ? int(status.fraction * 10.0) : int(elapsed / 10.0);
  const std::uint32_t judgement = progress_.judgements;
  const bool judged = !status.detail.empty() && judgement != last_judgement_;
  if (step <= last_step_ && !judged) return;
  last_step_ = std::max(step, last_step_), last_judgement_ = judgement;
  std::fprintf(stderr, "progress: %s\n", progress_line(status, now).c_str());
}

}  // namespace rtiow
