#include "python/watched_work.h"

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

namespace py = pybind11;

namespace rtiow::python {

Watched watch(const std::function<void()>& work, std::atomic<bool>& stop,
              const std::function<void()>& tick) {
  Watched w;
  std::mutex mutex;
  std::condition_variable ended;
  bool done = false;
  const py::gil_scoped_release released;
  std::thread worker([&] {
    try {
      work();
    } catch (...) {
      w.failure = std::current_exception();
    }
    const std::lock_guard lock(mutex);
    done = true;
    ended.notify_all();
  });
  for (;;) {
    {
      std::unique_lock lock(mutex);
      if (ended.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) break;
    }
    if (w.raised) continue;  // stopping: wait for the work's safe point
    const py::gil_scoped_acquire held;
    try {
      // KeyboardInterrupt, or what a signal handler raised; then the tick's own errors.
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (tick) tick();
    } catch (py::error_already_set& e) {
      w.raised.emplace(std::move(e));
      stop = true;
    }
  }
  worker.join();
  return w;
}

}  // namespace rtiow::python
