#pragma once
// What the denoiser's caller watches and stops it by: a stop asked between rows, and how far it
// has gone, for a display on another thread (a 4K frame denoises for half a minute on 2 cores).

#include <atomic>
#include <cstdint>
#include <functional>

namespace rtiow {

// `done` of `total` work as a share, 0 to 1 (0 without a total).
inline double denoise_fraction(std::uint64_t done, std::uint64_t total) {
  return total > 0 ? double(done < total ? done : total) / double(total) : 0.0;
}

// How far a denoise has gone: its work done of the whole, each pass's rows counted as they
// finish, by what a pixel of that pass costs (core/denoise/denoiser.cpp). `total` and `start_ns`
// are set as the denoise begins (0 before), `done` reaches `total` as it ends.
struct DenoiseProgress {
  std::atomic<std::uint64_t> done{0};
  std::atomic<std::uint64_t> total{0};
  std::atomic<std::int64_t> start_ns{0};  // steady clock, ns since its epoch

  // The share done, 0 to 1 (0 before it began).
  double fraction() const { return denoise_fraction(done.load(), total.load()); }
};

struct DenoiseControl {
  // Asked between rows; once it returns true it must stay true, and the denoiser throws
  // DenoiseCancelled soon after.
  std::function<bool()> cancelled;
  DenoiseProgress* progress = nullptr;
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
