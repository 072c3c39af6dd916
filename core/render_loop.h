#pragma once
// The sample loop: tbb::parallel_for over 16x16 tiles, all samples of a pixel inside one
// task, in sample order. Templated on the accelerator so each gets its own inlined loop
// (and so the benchmark can wrap one to record the rays it traces).

#include <oneapi/tbb/blocked_range2d.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <atomic>
#include <cstdint>
#include <vector>

#include "core/camera.h"
#include "core/film.h"
#include "core/integrator.h"
#include "core/render.h"
#include "core/sample_sum.h"
#include "core/thread_sanitizer.h"

namespace rtiow {

inline constexpr int kTileSize = 16;

// Adds samples [first, last) of pixel (x, y) to `sum`. The sum is exact (PixelSum), so it
// is the same whatever thread runs it and however the samples are split.
template <typename Accel>
void accumulate_pixel(const Scene& scene, const Camera& camera, const Accel& accel,
                      const RenderSettings& settings, int x, int y, std::uint64_t first,
                      std::uint64_t last, PixelSum& sum, std::uint64_t& rays) {
  const float inv_w = 1.0f / float(settings.width), inv_h = 1.0f / float(settings.height);
  for (std::uint64_t i = first; i < last; ++i) {
    SampleStream rng(settings.seed, std::uint32_t(x), std::uint32_t(y), i);
    const float s = (float(x) + rng.next_1d()) * inv_w;
    const float t = (float(y) + rng.next_1d()) * inv_h;
    float lens_u = 0.0f, lens_v = 0.0f;
    if (camera.has_lens()) lens_u = rng.next_1d(), lens_v = rng.next_1d();
    const Ray ray = camera.generate_ray(s, t, lens_u, lens_v);
    sum.add(trace_path(scene, accel, ray, settings.max_depth, rng, rays));
  }
}

// One pass: samples [first, last) of every pixel added to `sums` (width x height, row
// major). Returns the number of rays traced.
template <typename Accel>
std::uint64_t render_pass(const Scene& scene, const Camera& camera, const Accel& accel,
                          const RenderSettings& settings, std::uint64_t first, std::uint64_t last,
                          std::vector<PixelSum>& sums, RenderProgress* progress) {
  std::atomic<std::uint64_t> rays{0};
  const int threads = settings.threads > 0 ? settings.threads : tbb::info::default_concurrency();
  tbb::task_arena arena(threads);
  char fork = 0, join = 0;  // their addresses name the fork and the join for TSan
  tsan_release(&fork);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range2d<int>(0, settings.height, kTileSize, 0, settings.width, kTileSize),
        [&](const tbb::blocked_range2d<int>& tile) {
          tsan_acquire(&fork);
          std::uint64_t tile_rays = 0;
          for (int y = tile.rows().begin(); y < tile.rows().end(); ++y) {
            for (int x = tile.cols().begin(); x < tile.cols().end(); ++x) {
              PixelSum& sum = sums[std::size_t(y) * std::size_t(settings.width) + std::size_t(x)];
              accumulate_pixel(scene, camera, accel, settings, x, y, first, last, sum, tile_rays);
            }
          }
          rays += tile_rays;
          if (progress) {
            progress->rays_traced += tile_rays;
            progress->samples_done +=
                std::uint64_t(tile.rows().size() * tile.cols().size()) * (last - first);
          }
          tsan_release(&join);
        },
        tbb::simple_partitioner());
  });
  tsan_acquire(&join);
  return rays.load();
}

// Renders every pixel of `film` (already sized) at all samples in one pass and returns the
// number of rays traced.
template <typename Accel>
std::uint64_t render_tiles(const Scene& scene, const Camera& camera, const Accel& accel,
                           const RenderSettings& settings, Film& film, RenderProgress* progress) {
  std::vector<PixelSum> sums(std::size_t(settings.width) * std::size_t(settings.height));
  const std::uint64_t first = settings.first_sample;
  const std::uint64_t rays =
      render_pass(scene, camera, accel, settings, first,
                  first + std::uint64_t(settings.samples_per_pixel), sums, progress);
  resolve(sums, std::uint64_t(settings.samples_per_pixel), film);
  return rays;
}

}  // namespace rtiow
