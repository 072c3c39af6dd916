#pragma once
// The denoiser's progress on stderr while it runs after a render or a merge (a 4K frame takes
// half a minute on 2 cores, in which nothing else is said): on a terminal a live line once it
// has run half a second, erased as it ends; otherwise, once it has run two seconds, a plain
// line per tenth ("progress:", as the render's), none once a signal has asked for the end.

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>

#include "core/denoise/denoise_control.h"
#include "core/session/status_line.h"

namespace rtiow {

// " 45.0% denoised  elapsed 2.8s  ETA 3.4s", `done` of `total` work `elapsed` seconds in (the
// time to go at the rate so far; "?" before any is done).
std::string denoise_progress_line(std::uint64_t done, std::uint64_t total, double elapsed);

class DenoiseDisplay {
 public:
  // Shows `progress` until destroyed; plain lines stop once `stop_requested` (if given) is set.
  explicit DenoiseDisplay(const DenoiseProgress& progress,
                          const std::atomic<bool>* stop_requested = nullptr);
  ~DenoiseDisplay();  // stops the thread and erases the live line
  DenoiseDisplay(const DenoiseDisplay&) = delete;
  DenoiseDisplay& operator=(const DenoiseDisplay&) = delete;

 private:
  void report();

  const DenoiseProgress& progress_;
  const std::atomic<bool>* stop_requested_;
  const bool terminal_;
  bool drawn_ = false;  // a live line is on the terminal
  int last_tenth_ = 0;  // the last tenth a plain line reported
  std::optional<PeriodicReport> thread_;
};

}  // namespace rtiow
