#pragma once
// Every signal whose default action ends the process ends rtiow in its own words, in every
// command and every phase, with what it was writing removed (core/io/removed_on_abort.h) and
// what it had kept (an image, a checkpoint) left as it was:
//  - A request to end (SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGVTALRM,
//    SIGPROF, SIGXCPU, SIGIO, SIGPWR, SIGSTKFLT, the real-time signals): outside a render, rtiow
//    ends at once. During a render command (from the scene's load to the image's write), the
//    first asks the render to stop at the end of the current step (so the samples completed
//    are written, not lost); the second ends it at once, as outside.
//  - A fault of rtiow itself (SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGTRAP, SIGSYS): it
//    ends at once, said as an internal error.
// SIGPIPE and SIGXFSZ are ignored instead (main): the write fails and is reported. A signal
// ignored when rtiow started (a background job of a script, nohup) stays ignored. The line
// goes to the standard error rtiow started with, even while a library has it silenced.

#include <atomic>
#include <csignal>

namespace rtiow {

// Installs the end-at-once handlers for the whole process (main calls it first).
void end_at_once_on_signals();

// For a helper whose parent rtiow reports the signal (bench's points): a terminal's Ctrl-C
// reaches the whole process group, and one line a signal is the parent's. The helper still
// removes what it was writing and ends with 128 + the signal.
void end_quietly_on_signals();

class InterruptGuard {
 public:
  // Installs the stop-first handlers; `stop` is set on the first signal. Only one guard may
  // live.
  explicit InterruptGuard(std::atomic<bool>& stop);
  ~InterruptGuard();  // restores the previous handlers (the end-at-once ones)
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  // The signal that asked to stop, or 0.
  static int signal_received();

 private:
  struct sigaction previous_[NSIG] {};
};

// While one lives, the end-at-once of a second request to end waits for its end: the final
// write of a render (the image renamed into place, then the checkpoint it finishes removed)
// leaves either the state before it or the state after it, never a finished image beside a
// checkpoint that says less (issue 69). An image still being denoised then stops being denoised
// (core/parallel/cancellation.h) and is written as rendered, so the wait is the write's, not the
// denoiser's seconds. A fault still ends at once.
class FinalWrite {
 public:
  explicit FinalWrite(bool denoises = false);  // `denoises`: the image is to be denoised
  ~FinalWrite();  // ends rtiow, in its words, if a second signal came meanwhile
  FinalWrite(const FinalWrite&) = delete;
  FinalWrite& operator=(const FinalWrite&) = delete;
};

// Whether `signal` is one rtiow ends on in its own words (for the tests: every signal whose
// default action is to end the process, but SIGKILL, SIGSTOP, SIGPIPE and SIGXFSZ).
bool ends_in_rtiow_words(int signal);

}  // namespace rtiow
