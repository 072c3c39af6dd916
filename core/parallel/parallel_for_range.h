#pragma once
// tbb::parallel_for over an index range with its fork and join stated for ThreadSanitizer:
// for work outside a render (building a scene), in the calling arena, whose results must not
// depend on how TBB splits the range.

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/partitioner.h>

#include <cstddef>

#include "core/parallel/thread_sanitizer.h"

namespace rtiow {

// Calls body(begin, end) on disjoint chunks of [0, n) of at most `grain` indices, in parallel.
// The simple partitioner, as in the render loop: chunks of a fixed size need none of the
// auto partitioner's stealing flags, which uninstrumented libtbb orders out of TSan's sight
// (a flaky render_tests_tsan report in CI).
template <typename Body>
void parallel_for_range(std::size_t n, std::size_t grain, const Body& body) {
  const auto chunk = [&](const tbb::blocked_range<std::size_t>& part) {
    body(part.begin(), part.end());
  };
  tsan_release(&tsan_fork_sync);  // what the chunks read was written before this
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain),
                    TsanOrderedBody<decltype(chunk)>(chunk), tbb::simple_partitioner());
  tsan_acquire(&tsan_join_sync);  // every chunk's writes before the caller goes on
}

// body(i) for every index i < n, in parallel, `grain` indices a chunk: for loops whose every
// index's result is its own (a pixel's), the same for any split.
template <typename Body>
void for_each_index(std::size_t n, std::size_t grain, const Body& body) {
  parallel_for_range(n, grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) body(i);
  });
}

}  // namespace rtiow
