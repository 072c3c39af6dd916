#include "core/session/denoise_display.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace rtiow {
namespace {

// A denoise shorter than these shows nothing: its summary line follows at once.
constexpr double kLiveLineAfterSeconds = 0.5, kPlainLinesAfterSeconds = 2.0;

}  // namespace

std::string denoise_progress_line(std::uint64_t done, std::uint64_t total, double elapsed) {
  const double fraction = denoise_fraction(done, total);
  char share[32];
  std::snprintf(share, sizeof share, "%5.1f%%", 100.0 * fraction);
  const std::string to_go =
      done > 0 && total > 0 ? duration_text(elapsed * (1.0 - fraction) / fraction) : "?";
  return std::string(share) + " denoised  elapsed " + duration_text(elapsed) + "  ETA " + to_go;
}

DenoiseDisplay::DenoiseDisplay(const DenoiseProgress& progress,
                               const std::atomic<bool>* stop_requested)
    : progress_(progress), stop_requested_(stop_requested), terminal_(stderr_is_terminal()) {
  thread_.emplace(std::chrono::milliseconds(terminal_ ? 250 : 500), [this] { report(); });
}

DenoiseDisplay::~DenoiseDisplay() {
  thread_.reset();
  if (drawn_) erase_live_line();
}

void DenoiseDisplay::report() {
  const std::int64_t start = progress_.start_ns.load();
  const std::uint64_t total = progress_.total.load(), done = progress_.done.load();
  if (start == 0 || total == 0) return;  // not begun
  if (done >= total) {  // ended: what follows (the image's write) is not the denoiser's
    if (drawn_) erase_live_line();
    drawn_ = false;
    return;
  }
  const std::int64_t now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                               std::chrono::steady_clock::now().time_since_epoch())
                               .count();
  const double elapsed = double(now - start) * 1e-9;
  if (terminal_) {
    if (elapsed < kLiveLineAfterSeconds) return;
    draw_live_line(denoise_progress_line(done, total, elapsed));
    drawn_ = true;
    return;
  }
  if (elapsed < kPlainLinesAfterSeconds || (stop_requested_ && stop_requested_->load())) return;
  const int tenth = int(10 * done / total);
  if (tenth <= last_tenth_) return;
  last_tenth_ = tenth;
  std::fprintf(stderr, "progress: %s\n", denoise_progress_line(done, total, elapsed).c_str());
}

}  // namespace rtiow
