#pragma once
// What the denoiser's caller watches and stops it by: a stop asked between rows, and how far it
// has gone, for a display on another thread (a 4K frame denoises for half a minute on 2 cores).

#include <cstdint>
#include <functional>

#include "core/parallel/work_progress.h"

namespace rtiow {

struct DenoiseControl {
  // Asked between rows, from the denoiser's threads at once (so safe to call concurrently);
  // once it returns true it must stay true, and the denoiser throws DenoiseCancelled soon after.
  std::function<bool()> cancelled;
  // The passes' rows counted as they finish, each pixel by what its pass costs
  // (core/denoise/denoiser.cpp); begun as the denoise begins.
  WorkProgress* progress = nullptr;
  // What one pixel of the pass being run adds to `progress`.
  std::uint64_t work_per_pixel = 1;

  bool stop() const { return cancelled && cancelled(); }
  // `pixels` of the pass done.
  void advance(std::uint64_t pixels) const {
    if (progress) progress->done.fetch_add(pixels * work_per_pixel, std::memory_order_relaxed);
  }
  // The same control for a pass whose pixels cost `work` each.
  DenoiseControl pass(std::uint64_t work) const { return {cancelled, progress, work}; }
};

}  // namespace rtiow
