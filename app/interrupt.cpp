#include "app/interrupt.h"

#include <unistd.h>

#include "core/io/removed_on_abort.h"

namespace rtiow {
namespace {

static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");
std::atomic<bool>* g_stop = nullptr;
volatile std::sig_atomic_t g_signal = 0;
// A live progress line is on stderr only when it is a terminal: the messages below start on a
// line of their own there, and add no empty line to a log.
volatile std::sig_atomic_t g_terminal = 0;

void write_stderr(const char* text, std::size_t size) {
  // write(2) is async-signal-safe; the result is irrelevant in a handler.
  [[maybe_unused]] const ssize_t ignored = ::write(STDERR_FILENO, text, size);
}

// Async-signal-safe: no allocation, no stdio.
[[noreturn]] void end_at_once(int signal) {
  remove_files_now();
  constexpr char kHead[] = "\nrtiow: ended by signal ";
  constexpr char kTail[] = "; nothing more was written\n";
  char number[3] = {char('0' + signal / 10 % 10), char('0' + signal % 10), 0};
  const std::size_t skip = g_terminal ? 0 : 1;  // the line break before the text
  write_stderr(kHead + skip, sizeof kHead - 1 - skip);
  write_stderr(signal < 10 ? number + 1 : number, signal < 10 ? 1 : 2);
  write_stderr(kTail, sizeof kTail - 1);
  ::_exit(128 + signal);
}

void on_signal(int signal) {
  if (g_signal != 0) end_at_once(signal);
  g_signal = signal;
  if (g_stop) g_stop->store(true);
  constexpr char kStopping[] = "\nrtiow: stopping; a second signal ends rtiow at once\n";
  const std::size_t skip = g_terminal ? 0 : 1;
  write_stderr(kStopping + skip, sizeof kStopping - 1 - skip);
}

void install(void (*handler)(int), struct sigaction* previous) {
  struct sigaction action {};
  action.sa_handler = handler;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  for (std::size_t i = 0; i < std::size(kHandledSignals); ++i) {
    struct sigaction before {};
    sigaction(kHandledSignals[i], nullptr, &before);
    if (previous) previous[i] = before;
    if (before.sa_handler == SIG_IGN) continue;  // ignored by whoever started us
    sigaction(kHandledSignals[i], &action, nullptr);
  }
}

}  // namespace

void end_at_once_on_signals() {
  g_terminal = ::isatty(STDERR_FILENO) == 1;
  install(end_at_once, nullptr);
}

InterruptGuard::InterruptGuard(std::atomic<bool>& stop) {
  g_stop = &stop;
  g_signal = 0;
  install(on_signal, previous_);
}

InterruptGuard::~InterruptGuard() {
  for (std::size_t i = 0; i < std::size(kHandledSignals); ++i) {
    sigaction(kHandledSignals[i], &previous_[i], nullptr);
  }
  g_stop = nullptr;
}

int InterruptGuard::signal_received() {
  return int(g_signal);
}

}  // namespace rtiow
