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
#include <functional>
#include <vector>

#include "core/camera.h"
#include "core/film.h"
#include "core/integrator.h"
#include "core/pixel_variance.h"
#include "core/render.h"
#include "core/sample_sum.h"
#include "core/thread_sanitizer.h"

namespace rtiow {

inline constexpr int kTileSize = 16;

// Adds samples [first, last) of pixel (x, y) to `sum` and `squares`. The sum is exact
// (PixelSum), so it is the same whatever thread runs it and however the samples are split.
template <typename Accel>
void accumulate_pixel(const Scene& scene, const Camera& camera, const Accel& accel,
                      const RenderSettings& settings, int x, int y, std::uint64_t first,
                      std::uint64_t last, PixelSum& sum, PixelSquares& squares,
                      std::uint64_t& rays) {
  const float inv_w = 1.0f / float(settings.width), inv_h = 1.0f / float(settings.height);
  const int sobol_dimensions = settings.sampler == SamplerKind::Sobol ? kSobolSampledDimensions : 0;
  for (std::uint64_t i = first; i < last; ++i) {
    SampleStream rng(settings.seed, std::uint32_t(x), std::uint32_t(y), i, sobol_dimensions);
    const float s = (float(x) + rng.next_1d()) * inv_w;
    const float t = (float(y) + rng.next_1d()) * inv_h;
    float lens_u = 0.0f, lens_v = 0.0f;
    if (camera.has_lens()) {
      lens_u = rng.next_1d(), lens_v = rng.next_1d();
    } else {
      rng.skip(2);
    }
    const Ray ray = camera.generate_ray(s, t, lens_u, lens_v);
    const Color value = trace_path(scene, accel, ray, settings.max_depth, rng, rays);
    sum.add(value);
    squares.add(value);
  }
}

// The per-pixel state of a render in progress (row major, film-sized).
struct PixelAccumulators {
  std::vector<PixelSum> sums;
  std::vector<PixelSquares> squares;
  std::vector<std::uint32_t> samples;  // how many each pixel has, from the first sample

  explicit PixelAccumulators(std::size_t pixels)
      : sums(pixels), squares(pixels), samples(pixels, 0) {}
};

// One pass over the image: each pixel p is brought from its current count to
// `target(p, sum, squares, count)` samples (no change when the target is not above it).
// When `may_skip` is given, a tile is left untouched once it returns true (a stop request
// or a deadline mid-pass; only renders whose pixels keep their own counts may use it).
// Returns the number of rays traced.
template <typename Accel, typename Target>
std::uint64_t render_pass(const Scene& scene, const Camera& camera, const Accel& accel,
                          const RenderSettings& settings, const Target& target,
                          PixelAccumulators& pixels, RenderProgress* progress,
                          const std::function<bool()>& may_skip = {}) {
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
          if (may_skip && may_skip()) {
            tsan_release(&join);
            return;
          }
          std::uint64_t tile_rays = 0, tile_samples = 0;
          for (int y = tile.rows().begin(); y < tile.rows().end(); ++y) {
            for (int x = tile.cols().begin(); x < tile.cols().end(); ++x) {
              const std::size_t p = std::size_t(y) * std::size_t(settings.width) + std::size_t(x);
              std::uint32_t& count = pixels.samples[p];
              const std::uint32_t wanted = target(pixels.sums[p], pixels.squares[p], count);
              if (wanted <= count) continue;
              accumulate_pixel(scene, camera, accel, settings, x, y, settings.first_sample + count,
                               settings.first_sample + wanted, pixels.sums[p], pixels.squares[p],
                               tile_rays);
              tile_samples += wanted - count;
              count = wanted;
            }
          }
          rays += tile_rays;
          if (progress) {
            progress->rays_traced += tile_rays;
            progress->samples_done += tile_samples;
          }
          tsan_release(&join);
        },
        tbb::simple_partitioner());
  });
  tsan_acquire(&join);
  return rays.load();
}

// A pass target that brings every pixel to `n` samples.
inline auto every_pixel_to(std::uint32_t n) {
  return [n](const PixelSum&, const PixelSquares&, std::uint32_t) { return n; };
}

// Renders every pixel of `film` (already sized) at all samples in one pass and returns the
// number of rays traced.
template <typename Accel>
std::uint64_t render_tiles(const Scene& scene, const Camera& camera, const Accel& accel,
                           const RenderSettings& settings, Film& film, RenderProgress* progress) {
  PixelAccumulators pixels(std::size_t(settings.width) * std::size_t(settings.height));
  const auto n = std::uint32_t(settings.samples_per_pixel);
  const std::uint64_t rays =
      render_pass(scene, camera, accel, settings, every_pixel_to(n), pixels, progress);
  resolve(pixels.sums, n, film);
  return rays;
}

}  // namespace rtiow
