#pragma once
// Progress on stderr of the work after a render or around a merge (the parts read, the
// denoiser: a 4K frame denoises for half a minute on 2 cores, in which nothing else is said),
// phase by phase: on a terminal a live line once a phase has run half a second, erased as it
// ends; otherwise, once a phase has run two seconds, a plain line per tenth of it ("progress:",
// as the render's), none once a signal has asked for the end.

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/parallel/work_progress.h"
#include "core/session/status_line.h"

namespace rtiow {

// " 45.0% denoised  elapsed 2.8s  ETA 3.4s": `done` of `total` work `elapsed` seconds in, the
// time to go at the rate so far ("?" before any is done); `what` says what the share is of.
std::string work_progress_line(const std::string& what, std::uint64_t done, std::uint64_t total,
                               double elapsed);

// A stretch of work a display follows, and what its line says it has done ("denoised").
struct WorkPhase {
  const WorkProgress* progress;
  std::string what;
};

class WorkDisplay {
 public:
  // Shows the last of `phases` that has begun, until destroyed; plain lines stop once
  // `stop_requested` (if given) is set.
  explicit WorkDisplay(std::vector<WorkPhase> phases,
                       const std::atomic<bool>* stop_requested = nullptr);
  ~WorkDisplay();  // stops the thread and erases the live line
  WorkDisplay(const WorkDisplay&) = delete;
  WorkDisplay& operator=(const WorkDisplay&) = delete;

 private:
  void report();

  const std::vector<WorkPhase> phases_;
  const std::atomic<bool>* stop_requested_;
  const bool terminal_;
  bool drawn_ = false;   // a live line is on the terminal
  int last_phase_ = -1;  // the phase the last plain line reported
  int last_tenth_ = 0;   // and the tenth of it
  std::optional<PeriodicReport> thread_;
};

}  // namespace rtiow
