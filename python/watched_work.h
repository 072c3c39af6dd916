#pragma once
// Work that may take long (a render, a denoise, a merge) run as a good citizen of Python: on a
// thread of its own with the GIL released, while the caller's thread wakes every 50 ms, holding
// the GIL, to look for a signal (Ctrl-C) and to call a tick (a progress callback). A signal, or
// what the tick raises, sets `stop`, which the work heeds at its next safe point, and is kept to
// be raised once the work has ended and its result is put where it goes.

#include <pybind11/pybind11.h>

#include <atomic>
#include <exception>
#include <functional>
#include <optional>
#include <utility>

namespace rtiow::python {

struct Watched {
  std::exception_ptr failure;                         // what the work threw
  std::optional<pybind11::error_already_set> raised;  // what Python raised while it ran
};

// `tick` runs with the GIL held; a Python error it raises stops the work as a signal does.
Watched watch(const std::function<void()>& work, std::atomic<bool>& stop,
              const std::function<void()>& tick = {});

// `work(cancelled)` watched: returns its result, or raises what Python raised (KeyboardInterrupt,
// or what `tick` raised) once the work has heeded `cancelled` (or ended), or rethrows what the
// work threw.
template <typename T>
T interruptible(const std::function<T(const std::function<bool()>& cancelled)>& work,
                const std::function<void()>& tick = {}) {
  std::atomic<bool> stop{false};
  std::optional<T> out;
  Watched w = watch([&] { out.emplace(work([&] { return stop.load(); })); }, stop, tick);
  if (w.raised) throw std::move(*w.raised);
  if (w.failure) std::rethrow_exception(w.failure);
  return std::move(*out);
}

}  // namespace rtiow::python
