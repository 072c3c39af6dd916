#pragma once
// The thread count a user asked for (--threads), for all of the work it covers: the render's
// passes, and before them the scene's construction (or a big scene file's parse) and
// Embree's build, which use TBB's parallel loops of whatever arena calls them.
//
// TBB runs no more threads than the machine has cores unless told otherwise (and prints a
// warning of its own when an arena asks for more): a count above the cores raises TBB's limit
// for the work's duration, so the count asked is the count used, and TBB says nothing.

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/task_arena.h>

#include <optional>
#include <string>

#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/limits/setting_name.h"
#include "core/parallel/ieee_floating_point.h"
#include "core/parallel/thread_limit.h"

namespace rtiow {

// Refuses a count no work can run on: below 0, or beyond the pool TBB starts (every command that
// takes --threads says it in the same words).
inline void check_thread_count(int asked) {
  if (asked < 0 || asked > limits::kMaxThreads) {
    throw InvalidInput(setting("threads") + " must be from 0 (all cores) to " +
                       std::to_string(limits::kMaxThreads) + ", got " + std::to_string(asked));
  }
}

// 0: every core.
inline int thread_count(int asked) {
  return asked > 0 ? asked : tbb::info::default_concurrency();
}

// TBB's limit raised to `threads` while the result lives, where that is above the cores.
inline std::optional<tbb::global_control> allow_threads(int threads) {
  std::optional<tbb::global_control> more_than_cores;
  if (threads > tbb::info::default_concurrency()) {
    more_than_cores.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  }
  return more_than_cores;
}

// f() with TBB's parallel work inside it on `asked` threads (0: every core).
template <typename F>
auto with_threads(int asked, F&& f) {
  const int threads = thread_count(asked);
  require_threads(threads);
  const std::optional<tbb::global_control> allowed = allow_threads(threads);
  const IeeeFloatingPoint ieee;  // the arena's settings, whatever the caller's
  tbb::task_arena arena(threads);
  return arena.execute(f);
}

}  // namespace rtiow
