#pragma once
// Happens-before annotations for ThreadSanitizer. Debian's oneTBB and Embree are not built
// with TSan, so it cannot see that a parallel_for's tasks start after the caller's writes
// and finish before the caller continues; these calls state exactly that (and nothing
// more), so races between tasks are still reported. Without TSan they compile to nothing.

#if defined(__SANITIZE_THREAD__)
extern "C" void __tsan_acquire(void* address);
extern "C" void __tsan_release(void* address);
#endif

#include <utility>

namespace rtiow {

inline void tsan_release([[maybe_unused]] const void* sync) {
#if defined(__SANITIZE_THREAD__)
  __tsan_release(const_cast<void*>(sync));
#endif
}

inline void tsan_acquire([[maybe_unused]] const void* sync) {
#if defined(__SANITIZE_THREAD__)
  __tsan_acquire(const_cast<void*>(sync));
#endif
}

// Their addresses name the fork and the join of parallel loops: fixed addresses, so a task
// reads no shared memory before it acquires.
inline char tsan_fork_sync, tsan_join_sync;

// A parallel loop's body as TBB copies it into its tasks. The caller releases tsan_fork_sync
// after writing what the body reads and acquires tsan_join_sync after the loop; each call
// acquires the fork before it runs and releases the join after. Tasks are not ordered with
// each other, so races between them are still reported. The copies themselves live in TBB's
// task pool, reused out of TSan's sight: tests/tsan.supp suppresses races whose innermost
// frame is this class (its pointer to the body), and nothing else of it.
template <typename Body>
class TsanOrderedBody {
 public:
  explicit TsanOrderedBody(const Body& body) : body_(&body) {}
  TsanOrderedBody(const TsanOrderedBody& other) = default;
  TsanOrderedBody& operator=(const TsanOrderedBody&) = delete;

  template <typename Range>
  void operator()(const Range& part) const {
    tsan_acquire(&tsan_fork_sync);
    const Body& body = *body_;
    body(part);
    tsan_release(&tsan_join_sync);
  }

 private:
  const Body* body_;
};

// A parallel pipeline's stage as TBB copies it into its filters, ordered as TsanOrderedBody
// orders a loop's body: the copy holds a pointer to the stage (on the caller's stack, written
// before the caller releases tsan_fork_sync) and acquires the fork before it reads the stage.
// The copy lives in TBB's memory, written on the caller's thread and read on a worker out of
// TSan's sight (a flaky unit_tests_tsan report in CI, the lambda's capture read at the scene
// reader's pipeline): tests/tsan.supp suppresses races whose innermost frame is this class.
template <typename Body>
class TsanPipelineStage {
 public:
  explicit TsanPipelineStage(const Body& body) : body_(&body) {}

  template <typename... Args>
  auto operator()(Args&&... args) const {
    tsan_acquire(&tsan_fork_sync);
    return (*body_)(std::forward<Args>(args)...);
  }

 private:
  const Body* body_;
};

}  // namespace rtiow
