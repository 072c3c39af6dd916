#pragma once
// Ctrl-C and SIGTERM during a render: the first asks the render to stop at the end of the
// current pass (so the samples completed are written, not lost); the second aborts at once.

#include <atomic>
#include <csignal>

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
  struct sigaction previous_int_ {};
  struct sigaction previous_term_ {};
};

}  // namespace rtiow
