#pragma once
// A request to stop work that has no step of its own to stop at: building a scene of many
// spheres, committing its BVH, parsing a large scene file. The command line points this at
// its stop flag (set by a signal, app/interrupt.h); those builds poll it every few thousand
// spheres and throw Cancelled, so a signal is honoured within a fraction of a second instead
// of after minutes of building.

#include <atomic>
#include <stdexcept>

namespace rtiow {

struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("cancelled by a request to stop") {}
};

// The flag the builds poll; nullptr (the default) for none.
void set_cancellation_flag(const std::atomic<bool>* flag);

// Whether a stop was asked for.
bool cancellation_requested();

// Throws Cancelled when a stop was asked for.
inline void throw_if_cancelled() {
  if (cancellation_requested()) throw Cancelled();
}

// A request to end during a render's final write (a second signal, which waits for the image):
// what is still being made for it, its denoising, stops, and the image is written as rendered
// rather than after the denoiser's seconds. The command line points this at its signal
// handler's flag while it writes; nullptr (the default) for none.
void set_final_write_stop_flag(const std::atomic<bool>* flag);

// Whether such an end was asked for.
bool final_write_stop_requested();

}  // namespace rtiow
