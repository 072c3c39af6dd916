#pragma once
// Happens-before annotations for ThreadSanitizer. Debian's oneTBB and Embree are not built
// with TSan, so it cannot see that a parallel_for's tasks start after the caller's writes
// and finish before the caller continues; these calls state exactly that (and nothing
// more), so races between tasks are still reported. Without TSan they compile to nothing.

#if defined(__SANITIZE_THREAD__)
extern "C" void __tsan_acquire(void* address);
extern "C" void __tsan_release(void* address);
#endif

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

}  // namespace rtiow
