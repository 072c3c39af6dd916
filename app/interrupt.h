#pragma once
// A signal that would end the process during a render (Ctrl-C, SIGTERM, a hang-up from a
// closed terminal or SSH session, SIGQUIT, a batch system's CPU-time limit SIGXCPU): the
// first asks the render to stop at the end of the current pass (so the samples completed are
// written, not lost); the second aborts at once. A signal ignored when rtiow started (a
// background job of a script, nohup) stays ignored.

#include <atomic>
#include <csignal>
#include <iterator>

namespace rtiow {

class InterruptGuard {
 public:
  // Installs the handlers; `stop` is set on the first signal. Only one guard may live.
  explicit InterruptGuard(std::atomic<bool>& stop);
  ~InterruptGuard();  // restores the previous handlers
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  // The signal that asked to stop, or 0.
  static int signal_received();

 private:
  static constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGXCPU};
  struct sigaction previous_[std::size(kSignals)]{};
};

}  // namespace rtiow
