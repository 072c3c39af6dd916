#include "app/interrupt.h"

#include <fcntl.h>
#include <string.h>
#include <unistd.h>

#include <cstdlib>

#include "core/io/removed_on_abort.h"
#include "core/parallel/cancellation.h"

namespace rtiow {
namespace {

static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");
std::atomic<bool>* g_stop = nullptr;
volatile std::sig_atomic_t g_signal = 0;
// A live progress line is on stderr only when it is a terminal: the messages below start on a
// line of their own there, and add no empty line to a log.
volatile std::sig_atomic_t g_terminal = 0;
volatile std::sig_atomic_t g_quiet = 0;  // a helper: its parent says it
// Inside a FinalWrite: a second request waits in g_deferred for its end.
volatile std::sig_atomic_t g_final_write = 0;
volatile std::sig_atomic_t g_deferred = 0;
// Set with g_deferred: what the final write still makes (its denoising) stops.
std::atomic<bool> g_final_write_stop{false};
volatile std::sig_atomic_t g_final_write_denoises = 0;  // the image written is to be denoised
// The standard error rtiow started with, held apart: a library may point descriptor 2 at
// /dev/null for a while (core/io/oiio_image_backend.cpp), and rtiow's last line must not go
// there.
int g_stderr = STDERR_FILENO;

// The signals that ask a process to end, and those a fault of its own raises.
constexpr int kRequests[] = {SIGHUP,    SIGINT,  SIGQUIT, SIGTERM, SIGUSR1, SIGUSR2,  SIGALRM,
                             SIGVTALRM, SIGPROF, SIGXCPU, SIGIO,   SIGPWR,  SIGSTKFLT};
constexpr int kFaults[] = {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGTRAP, SIGSYS};

bool is_request(int signal) {
  for (const int s : kRequests) {
    if (s == signal) return true;
  }
  return signal >= SIGRTMIN && signal <= SIGRTMAX;
}

bool is_fault(int signal) {
  for (const int s : kFaults) {
    if (s == signal) return true;
  }
  return false;
}

// "SIGUSR1" for each signal, made before any handler can run: a handler only copies.
char g_names[NSIG][16];

void name_signals() {
  for (int s = 1; s < NSIG; ++s) {
    const char* abbrev = ::sigabbrev_np(s);
    char* out = g_names[s];
    if (abbrev) {
      std::size_t n = 0;
      for (const char* p = "SIG"; *p;) out[n++] = *p++;
      for (const char* p = abbrev; *p && n + 1 < sizeof g_names[s];) out[n++] = *p++;
      out[n] = '\0';
    } else if (s >= SIGRTMIN && s <= SIGRTMAX) {
      const int k = s - SIGRTMIN;  // "SIGRTMIN+k"
      std::size_t n = 0;
      for (const char* p = "SIGRTMIN"; *p;) out[n++] = *p++;
      if (k > 0) {
        out[n++] = '+';
        if (k >= 10) out[n++] = char('0' + k / 10);
        out[n++] = char('0' + k % 10);
      }
      out[n] = '\0';
    }
  }
}

void write_stderr(const char* text) {
  // write(2) is async-signal-safe; the result is irrelevant in a handler.
  [[maybe_unused]] const ssize_t ignored = ::write(g_stderr, text, ::strlen(text));
}

// Async-signal-safe: no allocation, no stdio.
[[noreturn]] void end_at_once(int signal) {
  remove_files_now();
  if (g_quiet) ::_exit(128 + signal);
  char number[4] = {char('0' + signal / 10 % 10), char('0' + signal % 10), 0, 0};
  const char* digits = signal < 10 ? number + 1 : number;
  write_stderr(g_terminal ? "\nrtiow: " : "rtiow: ");
  write_stderr(is_fault(signal) ? "internal error: ended by signal " : "ended by signal ");
  write_stderr(digits);
  if (g_names[signal][0] != '\0') {
    write_stderr(" (");
    write_stderr(g_names[signal]);
    write_stderr(")");
  }
  write_stderr("; nothing more was written\n");
  ::_exit(128 + signal);
}

void on_request(int signal) {
  if (g_signal != 0 && g_final_write && !g_quiet) {
    if (g_deferred == 0) {
      g_deferred = signal;
      g_final_write_stop.store(true);
      write_stderr(g_terminal ? "\nrtiow: finishing the write first"
                              : "rtiow: finishing the write first");
      write_stderr(g_final_write_denoises ? ", without denoising any further; then rtiow ends\n"
                                          : "; then rtiow ends\n");
    }
    return;
  }
  if (g_signal != 0 || g_quiet) end_at_once(signal);
  g_signal = signal;
  if (g_stop) g_stop->store(true);
  write_stderr(g_terminal ? "\nrtiow: stopping; a second signal ends rtiow at once\n"
                          : "rtiow: stopping; a second signal ends rtiow at once\n");
}

// Installs `handler` for the signals `which` picks, keeping what each had in `previous`.
void install(void (*handler)(int), bool (*which)(int), struct sigaction* previous) {
  struct sigaction action {};
  action.sa_handler = handler;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART | SA_ONSTACK;
  for (int s = 1; s < NSIG; ++s) {
    if (!which(s)) continue;
    struct sigaction before {};
    if (sigaction(s, nullptr, &before) != 0) continue;  // one glibc keeps for itself
    if (previous) previous[s] = before;
    if (before.sa_handler == SIG_IGN) continue;  // ignored by whoever started us
    sigaction(s, &action, nullptr);
  }
}

bool is_fault_to_handle(int signal) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  (void)signal;
  return false;  // the sanitizer's own report is worth more
#else
  return is_fault(signal);
#endif
}

// A stack for the handler, so that a stack overflow (SIGSEGV) is said too.
void give_handlers_a_stack() {
  static char stack[1 << 16];
  stack_t alternate{};
  alternate.ss_sp = stack;
  alternate.ss_size = sizeof stack;
  ::sigaltstack(&alternate, nullptr);
}

}  // namespace

bool ends_in_rtiow_words(int signal) {
  return is_request(signal) || is_fault(signal);
}

void end_at_once_on_signals() {
  g_terminal = ::isatty(STDERR_FILENO) == 1;
  const int held = ::fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 3);
  if (held >= 0) g_stderr = held;
  name_signals();
  give_handlers_a_stack();
  install(end_at_once, is_request, nullptr);
  install(end_at_once, is_fault_to_handle, nullptr);
}

void end_quietly_on_signals() {
  g_quiet = 1;
}

InterruptGuard::InterruptGuard(std::atomic<bool>& stop) {
  g_stop = &stop;
  g_signal = 0;
  set_cancellation_flag(&stop);  // long builds stop too (core/parallel/cancellation.h)
  install(on_request, is_request, previous_);
}

InterruptGuard::~InterruptGuard() {
  for (int s = 1; s < NSIG; ++s) {
    if (is_request(s)) sigaction(s, &previous_[s], nullptr);
  }
  set_cancellation_flag(nullptr);
  g_stop = nullptr;
}

FinalWrite::FinalWrite(bool denoises) {
  g_final_write_denoises = denoises ? 1 : 0;
  g_final_write_stop.store(false);
  set_final_write_stop_flag(&g_final_write_stop);
  g_final_write = 1;
}

FinalWrite::~FinalWrite() {
  g_final_write = 0;
  set_final_write_stop_flag(nullptr);
  if (g_deferred != 0) end_at_once(int(g_deferred));
}

int InterruptGuard::signal_received() {
  return int(g_signal);
}

}  // namespace rtiow
