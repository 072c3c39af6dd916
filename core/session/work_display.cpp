#include "core/session/work_display.h"

#include <chrono>
#include <cstdio>
#include <utility>

namespace rtiow {
namespace {

// A phase shorter than these shows nothing: what follows it comes at once.
constexpr double kLiveLineAfterSeconds = 0.5, kPlainLinesAfterSeconds = 2.0;

}  // namespace

std::string work_progress_line(const std::string& what, std::uint64_t done, std::uint64_t total,
                               double elapsed) {
  const double fraction = work_fraction(done, total);
  char share[32];
  std::snprintf(share, sizeof share, "%5.1f%%", 100.0 * fraction);
  const std::string to_go =
      done > 0 && total > 0 ? duration_text(elapsed * (1.0 - fraction) / fraction) : "?";
  return std::string(share) + " " + what + "  elapsed " + duration_text(elapsed) + "  ETA " + to_go;
}

WorkDisplay::WorkDisplay(std::vector<WorkPhase> phases, const std::atomic<bool>* stop_requested)
    : phases_(std::move(phases)), stop_requested_(stop_requested), terminal_(stderr_is_terminal()) {
  thread_.emplace(std::chrono::milliseconds(terminal_ ? 250 : 500), [this] { report(); });
}

WorkDisplay::~WorkDisplay() {
  thread_.reset();
  if (drawn_) erase_live_line();
}

void WorkDisplay::report() {
  int phase = -1;  // the last begun
  for (int i = 0; i < int(phases_.size()); ++i)
    if (phases_[std::size_t(i)].progress->start_ns.load() != 0) phase = i;
  if (phase < 0) return;
  const WorkPhase& shown = phases_[std::size_t(phase)];
  const std::int64_t start = shown.progress->start_ns.load();
  const std::uint64_t total = shown.progress->total.load(), done = shown.progress->done.load();
  if (total == 0 || done >= total) {  // ended: what follows (a write, a merge) is not its own
    if (drawn_) erase_live_line();
    drawn_ = false;
    return;
  }
  const std::int64_t now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                               std::chrono::steady_clock::now().time_since_epoch())
                               .count();
  const double elapsed = double(now - start) * 1e-9;
  const std::string line = work_progress_line(shown.what, done, total, elapsed);
  if (terminal_) {
    if (elapsed < kLiveLineAfterSeconds) return;
    draw_live_line(line);
    drawn_ = true;
    return;
  }
  if (elapsed < kPlainLinesAfterSeconds || (stop_requested_ && stop_requested_->load())) return;
  const int tenth = int(10 * done / total);
  if (phase == last_phase_ && tenth <= last_tenth_) return;
  last_phase_ = phase, last_tenth_ = tenth;
  std::fprintf(stderr, "progress: %s\n", line.c_str());
}

}  // namespace rtiow
