#pragma once
// How many threads can run at once, found by starting them: each started thread (with a small
// stack) waits at a gate until the last is tried, then all are released and joined. What a
// limit of processes (ulimit -u, a container's pids limit) or of memory allows is known only by
// trying. Header-only, so the image backend's module (core/io/oiio_image_backend.cpp), which
// links nothing of the core, asks the same way.

#include <pthread.h>

#include <mutex>
#include <vector>

namespace rtiow {

// The threads, up to `most`, that started beside the calling one; `error` gets pthread_create's
// reason for the first that did not (0 when all did).
inline int threads_that_can_start_together(int most, int* error = nullptr) {
  std::mutex gate;
  std::vector<pthread_t> started;
  int failed = 0;
  {
    const std::lock_guard<std::mutex> closed(gate);
    for (int i = 0; i < most; ++i) {
      pthread_attr_t small{};
      pthread_attr_init(&small);
      pthread_attr_setstacksize(&small, 1 << 16);
      pthread_t thread{};
      failed = ::pthread_create(
          &thread, &small,
          [](void* held) -> void* {
            const std::lock_guard<std::mutex> wait(*static_cast<std::mutex*>(held));
            return nullptr;
          },
          &gate);
      pthread_attr_destroy(&small);
      if (failed != 0) break;
      started.push_back(thread);
    }
  }
  for (const pthread_t thread : started) ::pthread_join(thread, nullptr);
  if (error) *error = failed;
  return int(started.size());
}

}  // namespace rtiow
