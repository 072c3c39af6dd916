#pragma once
// The sample loop: tbb::parallel_for over 16x16 tiles, all samples of a pixel inside one
// task, in sample order. Templated on the accelerator so each gets its own inlined loop
// (and so the benchmark can wrap one to record the rays it traces).

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/blocked_range2d.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/film/film.h"
#include "core/film/pixel_variance.h"
#include "core/film/sample_sum.h"
#include "core/render/integrator.h"
#include "core/render/render.h"
#include "core/render/thread_sanitizer.h"
#include "core/scene/camera.h"

namespace rtiow {

inline constexpr int kTileSize = 16;

// What every per-pixel function needs, passed as one: the scene, its camera, the
// accelerator built over it and the render's settings.
template <typename Accel>
struct RenderContext {
  const Scene& scene;
  const Camera& camera;
  const Accel& accel;
  const RenderSettings& settings;
};

// Adds samples [first, last) of pixel (x, y) to `sum` and `squares`. The sum is exact
// (PixelSum), so it is the same whatever thread runs it and however the samples are split.
template <typename Accel>
void accumulate_pixel(const RenderContext<Accel>& ctx, int x, int y, std::uint64_t first,
                      std::uint64_t last, PixelSum& sum, PixelSquares& squares,
                      std::uint64_t& rays) {
  const RenderSettings& settings = ctx.settings;
  const Camera& camera = ctx.camera;
  const float inv_w = 1.0f / float(settings.width), inv_h = 1.0f / float(settings.height);
  // The camera rays of kRayPacketSize samples go to the accelerator together (coherent: one
  // pixel); each path then goes on alone. Every sample has its own stream, so the image is
  // the one sample-by-sample tracing gives.
  const PixelSampler pixel(settings.sampler, settings.seed, std::uint32_t(x), std::uint32_t(y));
  std::array<std::optional<SampleStream>, kRayPacketSize> streams;
  std::array<Ray, kRayPacketSize> rays_out;
  std::array<std::optional<Hit>, kRayPacketSize> hits;
  for (std::uint64_t i = first; i < last; i += kRayPacketSize) {
    const int count = int(std::min<std::uint64_t>(kRayPacketSize, last - i));
    int traced = 0;  // the packet holds the samples whose first ray is traced, in order
    std::array<int, kRayPacketSize> slot;
    for (int k = 0; k < count; ++k) {
      SampleStream& rng = streams[std::size_t(k)].emplace(pixel, i + std::uint64_t(k));
      const std::array<float, 4> u = rng.next_camera();  // a pinhole ignores the lens's two
      const float s = (float(x) + u[0]) * inv_w;
      const float t = (float(y) + u[1]) * inv_h;
      const Ray ray = camera.generate_ray(s, t, u[2], u[3]);
      slot[std::size_t(k)] = starts_path(ray, settings.max_depth) ? traced : -1;
      if (slot[std::size_t(k)] >= 0) rays_out[std::size_t(traced++)] = ray;
    }
    intersect_packet(ctx.accel, rays_out.data(), traced, hits.data());
    rays += std::uint64_t(traced);
    for (int k = 0; k < count; ++k) {
      const int j = slot[std::size_t(k)];
      const Color value = j < 0 ? Color{}
                                : continue_path(ctx.scene, ctx.accel, rays_out[std::size_t(j)],
                                                hits[std::size_t(j)], settings.max_depth,
                                                *streams[std::size_t(k)], rays);
      sum.add(value);
      squares.add(value);
    }
  }
}

// The per-pixel state of a render in progress (row major, film-sized).
struct PixelAccumulators {
  std::vector<PixelSum> sums;
  std::vector<PixelSquares> squares;
  std::vector<std::uint32_t> samples;  // how many each pixel has, from the first sample
  std::vector<std::uint64_t> rays;     // how many rays they traced (adaptive sampling's cost)

  explicit PixelAccumulators(std::size_t pixels)
      : sums(pixels), squares(pixels), samples(pixels, 0), rays(pixels, 0) {}
};

// Runs `body` over `range` with tbb::parallel_for in an arena of the settings' thread
// count. The fork and the join are annotated for TSan, which does not see TBB's own.
template <typename Range, typename Body>
void parallel_over(const RenderSettings& settings, const Range& range, const Body& body) {
  const int threads = settings.threads > 0 ? settings.threads : tbb::info::default_concurrency();
  tbb::task_arena arena(threads);
  char fork = 0, join = 0;  // their addresses name the fork and the join for TSan
  tsan_release(&fork);
  arena.execute([&] {
    tbb::parallel_for(
        range,
        [&](const Range& part) {
          tsan_acquire(&fork);
          body(part);
          tsan_release(&join);
        },
        tbb::simple_partitioner());
  });
  tsan_acquire(&join);
}

// Brings pixel p from its current count to `wanted` samples; returns the samples added.
template <typename Accel>
std::uint64_t advance_pixel(const RenderContext<Accel>& ctx, std::size_t p, std::uint32_t wanted,
                            PixelAccumulators& pixels, std::uint64_t& rays) {
  std::uint32_t& count = pixels.samples[p];
  if (wanted <= count) return 0;
  const RenderSettings& settings = ctx.settings;
  const int x = int(p % std::size_t(settings.width)), y = int(p / std::size_t(settings.width));
  const std::uint64_t rays_before = rays;
  accumulate_pixel(ctx, x, y, settings.first_sample + count, settings.first_sample + wanted,
                   pixels.sums[p], pixels.squares[p], rays);
  pixels.rays[p] += rays - rays_before;
  const std::uint64_t added = wanted - count;
  count = wanted;
  return added;
}

// Adds a task's rays to the pass's total and its rays and samples to the progress counters.
inline void count_work(std::uint64_t task_rays, std::uint64_t task_samples,
                       std::atomic<std::uint64_t>& pass_rays, RenderProgress* progress) {
  pass_rays += task_rays;
  if (progress) {
    progress->rays_traced += task_rays;
    progress->samples_done += task_samples;
  }
}

// One pass over the image in 16x16 tiles: every pixel is brought to `samples` samples.
// Returns the number of rays traced.
template <typename Accel>
std::uint64_t render_pass(const RenderContext<Accel>& ctx, std::uint32_t samples,
                          PixelAccumulators& pixels, RenderProgress* progress) {
  const RenderSettings& settings = ctx.settings;
  std::atomic<std::uint64_t> rays{0};
  parallel_over(
      settings,
      tbb::blocked_range2d<int>(0, settings.height, kTileSize, 0, settings.width, kTileSize),
      [&](const tbb::blocked_range2d<int>& tile) {
        std::uint64_t tile_rays = 0, tile_samples = 0;
        for (int y = tile.rows().begin(); y < tile.rows().end(); ++y) {
          for (int x = tile.cols().begin(); x < tile.cols().end(); ++x) {
            const std::size_t p = std::size_t(y) * std::size_t(settings.width) + std::size_t(x);
            tile_samples += advance_pixel(ctx, p, samples, pixels, tile_rays);
          }
        }
        count_work(tile_rays, tile_samples, rays, progress);
      });
  return rays.load();
}

// A pass over a list of pixels (raster order), each brought to its entry of `targets`
// (film-sized): adaptive sampling's rounds, where few pixels may remain and tiles would
// leave threads idle. `may_skip` is asked before each group of pixels; once it returns
// true (a stop request, a deadline) the rest keep their counts. Returns the rays traced.
template <typename Accel>
std::uint64_t render_pixel_list(const RenderContext<Accel>& ctx,
                                const std::vector<std::size_t>& list,
                                const std::vector<std::uint32_t>& targets,
                                PixelAccumulators& pixels, RenderProgress* progress,
                                const std::function<bool()>& may_skip) {
  constexpr std::size_t kPixelsPerTask = 8;
  std::atomic<std::uint64_t> rays{0};
  parallel_over(ctx.settings, tbb::blocked_range<std::size_t>(0, list.size(), kPixelsPerTask),
                [&](const tbb::blocked_range<std::size_t>& part) {
                  if (may_skip()) return;
                  std::uint64_t part_rays = 0, part_samples = 0;
                  for (std::size_t i = part.begin(); i < part.end(); ++i) {
                    const std::size_t p = list[i];
                    part_samples += advance_pixel(ctx, p, targets[p], pixels, part_rays);
                  }
                  count_work(part_rays, part_samples, rays, progress);
                });
  return rays.load();
}

// Renders every pixel of `film` (already sized) at all samples in one pass and returns the
// number of rays traced.
template <typename Accel>
std::uint64_t render_tiles(const RenderContext<Accel>& ctx, Film& film, RenderProgress* progress) {
  const RenderSettings& settings = ctx.settings;
  PixelAccumulators pixels(std::size_t(settings.width) * std::size_t(settings.height));
  const auto n = std::uint32_t(settings.samples_per_pixel);
  const std::uint64_t rays = render_pass(ctx, n, pixels, progress);
  resolve(pixels.sums, n, film);
  return rays;
}

}  // namespace rtiow
