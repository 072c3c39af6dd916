#include "app/progress_display.h"

#include <unistd.h>

#include <cstdio>
#include <system_error>

namespace rtiow {
namespace {

void format_duration(char* out, std::size_t size, double seconds) {
  if (seconds < 60.0) {
    std::snprintf(out, size, "%.1fs", seconds);
  } else {
    const int total = int(seconds + 0.5);
    std::snprintf(out, size, "%dm%02ds", total / 60, total % 60);
  }
}

}  // namespace

ProgressDisplay::ProgressDisplay(const RenderProgress& progress, std::uint64_t total_samples)
    : progress_(progress),
      total_samples_(total_samples),
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
  if (total_samples_ == 0) {
    report_open_ended(final_report, elapsed);
    return;
  }
  const std::uint64_t done = progress_.samples_done, resumed = progress_.samples_resumed;
  const double fraction = total_samples_ ? double(done) / double(total_samples_) : 1;
  const double mrays = elapsed > 0 ? double(progress_.rays_traced) / elapsed * 1e-6 : 0.0;
  char elapsed_text[32], eta_text[32] = "?";
  format_duration(elapsed_text, sizeof elapsed_text, elapsed);
  // The samples still to do at this run's rate: a resumed render's checkpointed samples took
  // no time of this run, and counting them made the ETA 2-3x too short.
  const double to_go = seconds_to_go(done, resumed, total_samples_, elapsed);
  if (to_go >= 0.0) format_duration(eta_text, sizeof eta_text, to_go);

  if (terminal_) {
    std::fprintf(stderr, "\r\033[K%5.1f%%  elapsed %s  ETA %s  %.1f Mrays/s", 100.0 * fraction,
                 elapsed_text, eta_text, mrays);
    std::fflush(stderr);
    return;
  }
  // Not a terminal: one line per completed tenth, so a log stays short; none once a signal
  // has asked the render to stop (its "stopping" line is the last word until the summary).
  const int decile = int(fraction * 10.0);
  if (final_report || decile <= last_decile_ || progress_.stop_requested) return;
  last_decile_ = decile;
  std::fprintf(stderr, "progress: %3d%%  elapsed %s  ETA %s  %.1f Mrays/s\n", decile * 10,
               elapsed_text, eta_text, mrays);
}

// The total is not known in advance (adaptive sampling, a time limit without --spp): the
// samples done so far instead of a percentage, and no ETA.
void ProgressDisplay::report_open_ended(bool final_report, double elapsed) {
  const double mrays = elapsed > 0 ? double(progress_.rays_traced) / elapsed * 1e-6 : 0.0;
  char elapsed_text[32];
  format_duration(elapsed_text, sizeof elapsed_text, elapsed);
  const double samples = double(progress_.samples_done);
  if (terminal_) {
    std::fprintf(stderr, "\r\033[K%.3g samples  elapsed %s  %.1f Mrays/s", samples, elapsed_text,
                 mrays);
    std::fflush(stderr);
    return;
  }
  // Not a terminal: a line every ten seconds.
  const int tens = int(elapsed / 10.0);
  if (final_report || tens <= last_decile_ || progress_.stop_requested) return;
  last_decile_ = tens;
  std::fprintf(stderr, "progress: %.3g samples  elapsed %s  %.1f Mrays/s\n", samples, elapsed_text,
               mrays);
}

}  // namespace rtiow
