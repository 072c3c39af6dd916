#pragma once
// The thread count a user asked for (--threads), for all of the work it covers: the render's
// passes, and before them the scene's construction (or a big scene file's parse) and
// Embree's build, which use TBB's parallel loops of whatever arena calls them.

#include <oneapi/tbb/info.h>
#include <oneapi/tbb/task_arena.h>

namespace rtiow {

// 0: every core.
inline int thread_count(int asked) {
  return asked > 0 ? asked : tbb::info::default_concurrency();
}

// f() with TBB's parallel work inside it on at most `asked` threads (0: every core).
template <typename F>
auto with_threads(int asked, F&& f) {
  tbb::task_arena arena(thread_count(asked));
  return arena.execute(f);
}

}  // namespace rtiow
