#pragma once
// Progress on stderr while a render runs: a live line on a terminal, occasional plain
// lines otherwise (logs, CI). Runs on its own thread and only reads the render's counters;
// what it shows for each mode is core/session/progress_status.h's.

#include <chrono>
#include <cstdint>
#include <optional>

#include "core/render/render_settings.h"
#include "core/session/status_line.h"

namespace rtiow {

class ProgressDisplay {
 public:
  ProgressDisplay(const RenderProgress& progress, const RenderSettings& settings);
  ~ProgressDisplay();  // stops the thread and finishes the live line
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

 private:
  void report(bool final_report);

  const RenderProgress& progress_;
  const RenderSettings settings_;
  const std::uint64_t pixels_;
  const bool terminal_;
  const std::chrono::steady_clock::time_point start_;
  int last_step_ = 0;                 // the last tenth (or ten seconds) a plain line reported
  std::uint32_t last_judgement_ = 0;  // the last round judged that a plain line reported
  std::optional<PeriodicReport> thread_;
};

}  // namespace rtiow
