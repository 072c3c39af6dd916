#pragma once
// Progress on stderr while a render runs: a live line on a terminal, occasional plain
// lines otherwise (logs, CI). Runs on its own thread and only reads the render's counters.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

#include "core/render/render_settings.h"

namespace rtiow {

// Seconds until `total` samples are done at this run's rate: `done` of them are, `resumed` of
// those came from a checkpoint (they took none of the `elapsed` seconds). Negative when this
// run has done nothing yet, so there is no rate.
inline double seconds_to_go(std::uint64_t done, std::uint64_t resumed, std::uint64_t total,
                            double elapsed) {
  if (done <= resumed || done > total || elapsed <= 0.0) return -1.0;
  return double(total - done) * elapsed / double(done - resumed);
}

class ProgressDisplay {
 public:
  // `total_samples` 0: not known in advance; the display counts samples instead.
  ProgressDisplay(const RenderProgress& progress, std::uint64_t total_samples);
  ~ProgressDisplay();  // stops the thread and finishes the live line
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

 private:
  void run();
  void report(bool final_report);
  void report_open_ended(bool final_report, double elapsed);

  const RenderProgress& progress_;
  const std::uint64_t total_samples_;
  const bool terminal_;
  const std::chrono::steady_clock::time_point start_;
  int last_decile_ = 0;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace rtiow
