#pragma once
// Progress on stderr while a render runs: a live line on a terminal, occasional plain
// lines otherwise (logs, CI). Runs on its own thread and only reads the render's counters;
// what it shows for each mode is core/session/progress_status.h's.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "core/render/render_settings.h"

namespace rtiow {

// A progress line in at most `columns` characters: its leading fields that fit whole (the
// share first), or its first `columns` characters where not even the first does.
std::string fit_to_columns(const std::string& line, std::size_t columns);

class ProgressDisplay {
 public:
  ProgressDisplay(const RenderProgress& progress, const RenderSettings& settings);
  ~ProgressDisplay();  // stops the thread and finishes the live line
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

 private:
  void run();
  void report(bool final_report);

  const RenderProgress& progress_;
  const RenderSettings settings_;
  const std::uint64_t pixels_;
  const bool terminal_;
  const std::chrono::steady_clock::time_point start_;
  int last_step_ = 0;                 // the last tenth (or ten seconds) a plain line reported
  std::uint32_t last_judgement_ = 0;  // the last round judged that a plain line reported
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace rtiow
