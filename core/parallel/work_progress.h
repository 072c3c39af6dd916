#pragma once
// How far a stretch of work has gone (the denoiser's passes, the parts a merge reads), counted
// by the threads doing it for a display on another: its work done of the whole. `total` and
// `start_ns` are set as the work begins (0 before), `done` reaches `total` as it ends.

#include <atomic>
#include <chrono>
#include <cstdint>

namespace rtiow {

// `done` of `total` as a share, 0 to 1 (0 without a total).
inline double work_fraction(std::uint64_t done, std::uint64_t total) {
  return total > 0 ? double(done < total ? done : total) / double(total) : 0.0;
}

struct WorkProgress {
  std::atomic<std::uint64_t> done{0};
  std::atomic<std::uint64_t> total{0};
  std::atomic<std::int64_t> start_ns{0};  // steady clock, ns since its epoch

  // Starts it again: `work` to do from now.
  void begin(std::uint64_t work) {
    done = 0;
    total = work;
    start_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                   std::chrono::steady_clock::now().time_since_epoch())
                   .count();
  }
  // The share done, 0 to 1 (0 before it began).
  double fraction() const { return work_fraction(done.load(), total.load()); }
};

}  // namespace rtiow
