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

#include "core/camera.h"
#include "core/film.h"
#include "core/integrator.h"
#include "core/render.h"

namespace rtiow {

inline constexpr int kTileSize = 16;

// All samples of one pixel, in sample order: the sum is the same whatever thread runs it.
template <typename Accel>
Color render_pixel(const Scene& scene, const Camera& camera, const Accel& accel,
                   const RenderSettings& settings, int x, int y, std::uint64_t& rays) {
  Vec3d sum;
  const float inv_w = 1.0f / float(settings.width), inv_h = 1.0f / float(settings.height);
  for (int i = 0; i < settings.samples_per_pixel; ++i) {
    SampleStream rng(settings.seed, std::uint32_t(x), std::uint32_t(y), std::uint64_t(i));
    const float s = (float(x) + rng.next_1d()) * inv_w;
    const float t = (float(y) + rng.next_1d()) * inv_h;
    float lens_u = 0.0f, lens_v = 0.0f;
    if (camera.has_lens()) lens_u = rng.next_1d(), lens_v = rng.next_1d();
    const Ray ray = camera.generate_ray(s, t, lens_u, lens_v);
    sum += Vec3d(trace_path(scene, accel, ray, settings.max_depth, rng, rays));
  }
  return Color(sum / double(settings.samples_per_pixel));
}

// Renders every pixel of `film` (already sized) and returns the number of rays traced.
template <typename Accel>
std::uint64_t render_tiles(const Scene& scene, const Camera& camera, const Accel& accel,
                           const RenderSettings& settings, Film& film, RenderProgress* progress) {
  std::atomic<std::uint64_t> rays{0};
  const int threads = settings.threads > 0 ? settings.threads : tbb::info::default_concurrency();
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range2d<int>(0, settings.height, kTileSize, 0, settings.width, kTileSize),
        [&](const tbb::blocked_range2d<int>& tile) {
          std::uint64_t tile_rays = 0;
          for (int y = tile.rows().begin(); y < tile.rows().end(); ++y) {
            for (int x = tile.cols().begin(); x < tile.cols().end(); ++x) {
              film.at(x, y) = render_pixel(scene, camera, accel, settings, x, y, tile_rays);
            }
          }
          rays += tile_rays;
          if (progress) {
            progress->rays_traced += tile_rays;
            progress->pixels_done += std::uint64_t(tile.rows().size() * tile.cols().size());
          }
        },
        tbb::simple_partitioner());
  });
  return rays.load();
}

}  // namespace rtiow
