#pragma once
// The raw trace rate: how fast rtcIntersect1 alone runs on exactly the rays a render
// traced. The ratio render rate / trace rate says how close the whole renderer gets to
// pure traversal.

#include <cstdint>
#include <vector>

#include "core/accel/embree_accel.h"
#include "core/geometry/ray.h"
#include "core/render/render.h"
#include "core/scene/scene.h"

namespace rtiow {

// Renders `scene` once with Embree and returns every ray it traced (tile order).
std::vector<Ray> record_traced_rays(const Scene& scene, const RenderSettings& settings);

struct TraceRate {
  double seconds = 0.0;
  std::uint64_t rays = 0;
  std::uint64_t hits = 0;  // keeps the work observable, so it cannot be optimised away
  double mrays_per_second() const { return rtiow::mrays_per_second(double(rays), seconds); }
};

// Traces `rays` through Embree on `threads` threads (0: all cores), nothing else. With
// EmbreeCallback::Nothing, the sphere test is left out too: Embree's traversal alone.
TraceRate measure_trace_rate(const Scene& scene, const std::vector<Ray>& rays, int threads,
                             EmbreeCallback callback = EmbreeCallback::SphereTest);

}  // namespace rtiow
