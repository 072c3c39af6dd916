#pragma once
// A signal that would end the process (Ctrl-C, SIGTERM, a hang-up from a closed terminal or
// SSH session, SIGQUIT, a batch system's CPU-time limit SIGXCPU). Outside a render, rtiow ends
// at once in its own words, removing the temporary it was writing (core/io/removed_on_abort.h).
// During a render command (from the scene's load to the image's write), the first asks the
// render to stop at the end of the current step (so the samples completed are written, not
// lost); the second ends it at once, as outside. A signal ignored when rtiow started (a
// background job of a script, nohup) stays ignored.

#include <atomic>
#include <csignal>
#include <iterator>

namespace rtiow {

// Installs the end-at-once handlers for the whole process (main calls it first).
void end_at_once_on_signals();

inline constexpr int kHandledSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGXCPU};

class InterruptGuard {
 public:
  // Installs the handlers; `stop` is set on the first signal. Only one guard may live.
  explicit InterruptGuard(std::atomic<bool>& stop);
  ~InterruptGuard();  // restores the previous handlers (the end-at-once ones)
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  // The signal that asked to stop, or 0.
  static int signal_received();

 private:
  struct sigaction previous_[std::size(kHandledSignals)]{};
};

}  // namespace rtiow
