#include "core/session/progress_display.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <system_error>

#include "core/session/progress_status.h"

namespace rtiow {
namespace {

std::string duration(double seconds) {
  char text[32];
  if (seconds < 60.0) {
    std::snprintf(text, sizeof text, "%.1fs", seconds);
  } else {
    const long long total = (long long)(seconds + 0.5);
    std::snprintf(text, sizeof text, "%lldm%02llds", total / 60, total % 60);
  }
  return text;
}

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
  line += "  elapsed " + duration(now.elapsed);
  if (status.fraction >= 0.0) {
    line += "  ETA " + (status.seconds_to_go >= 0.0 ? duration(status.seconds_to_go) : "?");
  }
  if (!status.detail.empty()) line += "  " + status.detail;
  std::snprintf(text, sizeof text, "  %.1f Mrays/s", live_mrays_per_second(now));
  return line + text;
}

}  // namespace

std::string fit_to_columns(const std::string& line, std::size_t columns) {
  if (line.size() <= columns) return line;
  // Whole fields ("  ETA 9.3s") while they fit, the share first; a field cut in two misleads.
  std::string fitted;
  for (std::size_t start = 0; start < line.size();) {
    std::size_t next = line.find("  ", start + 1);
    if (next == std::string::npos) next = line.size();
    if (next > columns) break;
    fitted = line.substr(0, next);
    start = next;
  }
  return fitted.empty() ? line.substr(0, columns) : fitted;
}

ProgressDisplay::ProgressDisplay(const RenderProgress& progress, const RenderSettings& settings)
    : progress_(progress),
      settings_(settings),
      pixels_(std::uint64_t(film_width(settings)) * std::uint64_t(film_height(settings))),
      terminal_(::isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()) {
  try {
    thread_ = std::thread([this] { run(); });
  } catch (const std::system_error&) {
    // No thread to be had (a limit of processes): the render goes on without the live display,
    // and its final report is still printed.
  }
}

ProgressDisplay::~ProgressDisplay() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  report(true);
  if (terminal_) std::fputc('\n', stderr);
}

void ProgressDisplay::run() {
  const auto period = terminal_ ? std::chrono::milliseconds(250) : std::chrono::milliseconds(1000);
  std::unique_lock lock(mutex_);
  while (!wake_.wait_for(lock, period, [this] { return stop_; })) report(false);
}

void ProgressDisplay::report(bool final_report) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const ProgressSnapshot now = snapshot(progress_, elapsed);
  const ProgressStatus status = progress_status(settings_, pixels_, now);
  if (terminal_) {
    // One line that never wraps: a wrapped line is not erased by the next \r, and a narrow
    // terminal filled with copies of it.
    std::string line = progress_line(status, now);
    winsize size{};
    if (::ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 1)
      line = fit_to_columns(line, size.ws_col - 1);
    std::fprintf(stderr, "\r\033[K%s", line.c_str());
    std::fflush(stderr);
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
