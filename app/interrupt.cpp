#include "app/interrupt.h"

#include <unistd.h>

namespace rtiow {
namespace {

static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");
std::atomic<bool>* g_stop = nullptr;
volatile std::sig_atomic_t g_signal = 0;

void write_stderr(const char* text, std::size_t size) {
  // write(2) is async-signal-safe; the result is irrelevant in a handler.
  [[maybe_unused]] const ssize_t ignored = ::write(STDERR_FILENO, text, size);
}

void on_signal(int signal) {
  if (g_signal != 0) {
    constexpr char kAbort[] = "\nrtiow: aborted\n";
    write_stderr(kAbort, sizeof kAbort - 1);
    ::_exit(128 + signal);
  }
  g_signal = signal;
  if (g_stop) g_stop->store(true);
  constexpr char kStopping[] =
      "\nrtiow: stopping after the current pass to write the samples done (again to abort)\n";
  write_stderr(kStopping, sizeof kStopping - 1);
}

}  // namespace

InterruptGuard::InterruptGuard(std::atomic<bool>& stop) {
  g_stop = &stop;
  g_signal = 0;
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  for (std::size_t i = 0; i < std::size(kSignals); ++i) {
    sigaction(kSignals[i], nullptr, &previous_[i]);
    if (previous_[i].sa_handler == SIG_IGN) continue;  // ignored by whoever started us
    sigaction(kSignals[i], &action, nullptr);
  }
}

InterruptGuard::~InterruptGuard() {
  for (std::size_t i = 0; i < std::size(kSignals); ++i) {
    sigaction(kSignals[i], &previous_[i], nullptr);
  }
  g_stop = nullptr;
}

int InterruptGuard::signal_received() {
  return int(g_signal);
}

}  // namespace rtiow
