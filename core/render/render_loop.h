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
#include <type_traits>
#include <vector>

#include "core/film/film.h"
#include "core/film/pixel_variance.h"
#include "core/film/sample_sum.h"
#include "core/parallel/thread_count.h"
#include "core/parallel/thread_sanitizer.h"
#include "core/render/integrator.h"
#include "core/render/pixel_accumulators.h"
#include "core/render/render.h"
#include "core/scene/camera.h"

namespace rtiow {

class EmbreeAccel;
class NaiveAccel;

inline constexpr int kTileSize = 16;

// The tile size a pass splits the image into: kTileSize, or half of it when that would give
// fewer than eight tiles a thread (a small image on many cores), so that the last tiles do not
// leave threads idle. Any tiling gives the same image (a pixel's samples, their order and
// its exact sum do not depend on it).
inline int tile_size(int width, int height, int threads) {
  const long tiles =
      long((width + kTileSize - 1) / kTileSize) * long((height + kTileSize - 1) / kTileSize);
  return tiles < 8L * threads ? kTileSize / 2 : kTileSize;
}

// What every per-pixel function needs, passed as one: the scene, its camera, the
// accelerator built over it, the render's settings (their width and height the film's) and
// where the film lies in the frame (a crop).
template <typename Accel>
struct RenderContext {
  const Scene& scene;
  const Camera& camera;
  const Accel& accel;
  const RenderSettings& settings;
  FramePlacement frame{};
};

// A run of pixels of one row that all go from the same count to the same count: the unit
// the sample loop works on. One pixel is a run; a pass makes runs of a tile's rows.
struct PixelRun {
  int x, y;                   // the first pixel
  int length;                 // pixels, at most kTileSize
  std::uint64_t first, last;  // the samples each pixel takes, [first, last)
};

// The per-pixel state a run adds to, at the run's first pixel.
struct RunAccumulators {
  PixelSum* sums;
  PixelSpread* spreads;
  std::uint64_t* rays;                // rays traced per pixel
  FirstHitSum* first_hits = nullptr;  // what the passes average, where they are asked
};

// One packet of camera samples as it goes through the loop below: each sample's stream,
// pixel of the run and index, its camera ray's place among the traced ones (or -1), the
// traced rays and their hits.
struct SamplePacket {
  std::array<std::optional<SampleStream>, kRayPacketSize> streams;
  std::array<int, kRayPacketSize> owner;            // the pixel of the run each sample belongs to
  std::array<std::uint64_t, kRayPacketSize> index;  // and its sample index
  std::array<int, kRayPacketSize> slot;             // its camera ray's place in the packet, or -1
  std::array<Ray, kRayPacketSize> rays_out;
  std::array<std::optional<Hit>, kRayPacketSize> hits;
  Camera::Lanes lanes{};
  std::array<Ray, kRayPacketSize> camera_rays;
  int count = 0, traced = 0;  // the packet holds the samples whose first ray is traced
};

// Fills the packet's camera lanes with the next samples of the run, from sample i of the
// run's pixel `pixel` on, and moves both past them.
[[gnu::always_inline]] inline void next_camera_samples(
    SamplePacket& packet, const std::array<std::optional<PixelSampler>, kTileSize>& samplers,
    const PixelRun& run, int x0, int y, float inv_w, float inv_h, int& pixel, std::uint64_t& i) {
  packet.count = 0, packet.traced = 0;
  for (; packet.count < kRayPacketSize && pixel < run.length; ++packet.count) {
    const auto k = std::size_t(packet.count);
    SampleStream& rng = packet.streams[k].emplace(*samplers[std::size_t(pixel)], i);
    const std::array<float, 4> u = rng.next_camera();  // a pinhole ignores the lens's two
    packet.lanes.s[k] = (float(x0 + pixel) + u[0]) * inv_w;
    packet.lanes.t[k] = (float(y) + u[1]) * inv_h;
    packet.lanes.lens_u[k] = u[2], packet.lanes.lens_v[k] = u[3];
    packet.owner[k] = pixel;
    packet.index[k] = i;
    if (++i == run.last) {  // the pixel is done: the next one from its first sample
      i = run.first;
      ++pixel;
    }
  }
}

// Follows each of the packet's traced camera rays to the end of its path and adds every
// sample to its pixel; returns the rays traced.
template <typename Accel>
[[gnu::always_inline]] inline std::uint64_t add_packet_paths(const RenderContext<Accel>& ctx,
                                                             SamplePacket& packet,
                                                             RunAccumulators out) {
  const RenderSettings& settings = ctx.settings;
  std::uint64_t total_rays = 0;
  for (int k = 0; k < packet.count; ++k) {
    const int j = packet.slot[std::size_t(k)];
    const auto o = std::size_t(packet.owner[std::size_t(k)]);
    std::uint64_t path_rays = j < 0 ? 0 : 1;
    FirstHit first{};  // a sample not traced, or one that saw the sky, met nothing: zeros
    const Color value =
        j < 0 ? Color{}
              : continue_path(ctx.scene, ctx.accel, packet.rays_out[std::size_t(j)],
                              packet.hits[std::size_t(j)], settings.max_depth,
                              settings.russian_roulette, *packet.streams[std::size_t(k)], path_rays,
                              out.first_hits ? &first : nullptr);
    add_sample(out.sums[o], out.spreads[o], value, packet.index[std::size_t(k)]);
    if (out.first_hits) out.first_hits[o].add(first);
    out.rays[o] += path_rays;
    total_rays += path_rays;
  }
  return total_rays;
}

// Adds the run's samples to its pixels. The camera rays go to the accelerator
// kRayPacketSize at a time, pixel by pixel in sample order: a packet holds consecutive
// samples of one pixel or, when a pass gives each pixel fewer than a packet (a large image
// renders in passes of a few samples), of neighbouring pixels, so packets stay full whatever
// the pass size (a half-empty rtcIntersect8 costs a full one). Each path then goes on alone.
// Every sample has its own stream and each pixel's sum takes its samples in order, so the
// image is the one sample-by-sample tracing gives; the sum is exact (PixelSum), so it is the
// same whatever thread runs it and however the samples are split.
// Returns the rays traced.
template <typename Accel>
[[gnu::always_inline]] inline std::uint64_t accumulate_run_inlined(const RenderContext<Accel>& ctx,
                                                                   const PixelRun& run,
                                                                   RunAccumulators out) {
  const RenderSettings& settings = ctx.settings;
  // The frame's pixel the film's stands for: its samples and its camera rays are the ones the
  // whole frame's render gives it.
  const FramePlacement& frame = ctx.frame;
  const int frame_width = frame.frame_width > 0 ? frame.frame_width : settings.width;
  const int frame_height = frame.frame_height > 0 ? frame.frame_height : settings.height;
  const float inv_w = 1.0f / float(frame_width), inv_h = 1.0f / float(frame_height);
  const int x0 = run.x + frame.x, y = run.y + frame.y;
  std::array<std::optional<PixelSampler>, kTileSize> samplers;
  for (int j = 0; j < run.length; ++j) {
    samplers[std::size_t(j)].emplace(settings.sampler, settings.seed, std::uint32_t(x0 + j),
                                     std::uint32_t(y), replicates(settings));
  }
  static_assert(Camera::kLanes == kRayPacketSize);
  SamplePacket packet;
  std::uint64_t total_rays = 0;
  int pixel = run.first < run.last ? 0 : run.length;  // where the next packet starts ...
  std::uint64_t i = run.first;                        // ... and at which sample
  while (pixel < run.length) {
    next_camera_samples(packet, samplers, run, x0, y, inv_w, inv_h, pixel, i);
    ctx.camera.generate_rays(packet.lanes, packet.camera_rays.data());
    for (int k = 0; k < packet.count; ++k) {
      const Ray& ray = packet.camera_rays[std::size_t(k)];
      packet.slot[std::size_t(k)] = starts_path(ray, settings.max_depth) ? packet.traced : -1;
      if (packet.slot[std::size_t(k)] >= 0) packet.rays_out[std::size_t(packet.traced++)] = ray;
    }
    intersect_packet(ctx.accel, packet.rays_out.data(), packet.traced, packet.hits.data());
    total_rays += add_packet_paths(ctx, packet, out);
  }
  return total_rays;
}

// accumulate_run for the renderer's own accelerators, compiled for several instruction sets
// and chosen at run time (core/render/render_kernels.cpp).
std::uint64_t accumulate_run_dispatched(const RenderContext<EmbreeAccel>& ctx, const PixelRun& run,
                                        RunAccumulators out);
std::uint64_t accumulate_run_dispatched(const RenderContext<NaiveAccel>& ctx, const PixelRun& run,
                                        RunAccumulators out);

template <typename Accel>
std::uint64_t accumulate_run(const RenderContext<Accel>& ctx, const PixelRun& run,
                             RunAccumulators out) {
  if constexpr (std::is_same_v<Accel, EmbreeAccel> || std::is_same_v<Accel, NaiveAccel>) {
    return accumulate_run_dispatched(ctx, run, out);
  } else {
    return accumulate_run_inlined(ctx, run, out);
  }
}

// Runs `body` over `range` with tbb::parallel_for in an arena of the settings' thread
// count. The fork and the join are annotated for TSan, which does not see TBB's own.
template <typename Range, typename Body>
void parallel_over(const RenderSettings& settings, const Range& range, const Body& body) {
  const int threads = thread_count(settings.threads);
  const std::optional<tbb::global_control> allowed = allow_threads(threads);
  tbb::task_arena arena(threads);
  tsan_release(&tsan_fork_sync);  // what the tasks read was written before this
  arena.execute(
      [&] { tbb::parallel_for(range, TsanOrderedBody<Body>(body), tbb::simple_partitioner()); });
  tsan_acquire(&tsan_join_sync);  // every task's writes before the caller goes on
}

// Brings the n pixels pixel_at(0..n-1) (raster order) to target_of(pixel) samples each,
// consecutive pixels of one row with the same count and target as one run. Adds the rays
// traced to `rays`; returns the samples added.
template <typename Accel, typename PixelAt, typename TargetOf>
std::uint64_t advance_pixels(const RenderContext<Accel>& ctx, std::size_t n,
                             const PixelAt& pixel_at, const TargetOf& target_of,
                             PixelAccumulators& pixels, std::uint64_t& rays) {
  const auto width = std::size_t(ctx.settings.width);
  const std::uint64_t base = ctx.settings.first_sample;
  std::uint64_t added = 0;
  for (std::size_t k = 0; k < n;) {
    const std::size_t p = pixel_at(k);
    const std::uint32_t from = pixels.samples[p], to = target_of(p);
    std::size_t length = 1;
    for (; k + length < n && length < std::size_t(kTileSize); ++length) {
      const std::size_t q = pixel_at(k + length);
      if (q != p + length || q % width == 0 || pixels.samples[q] != from || target_of(q) != to) {
        break;
      }
    }
    k += length;
    if (to <= from) continue;
    const PixelRun run{int(p % width), int(p / width), int(length), base + from, base + to};
    FirstHitSum* first_hits = pixels.sums.first_hits.empty() ? nullptr : &pixels.sums.first_hits[p];
    rays += accumulate_run(
        ctx, run, {&pixels.sums.color[p], &pixels.sums.spreads[p], &pixels.rays[p], first_hits});
    std::fill_n(pixels.samples.begin() + std::ptrdiff_t(p), length, to);
    added += std::uint64_t(length) * (to - from);
  }
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
  const int side = tile_size(settings.width, settings.height, thread_count(settings.threads));
  parallel_over(settings,
                tbb::blocked_range2d<int>(0, settings.height, side, 0, settings.width, side),
                [&](const tbb::blocked_range2d<int>& tile) {
                  std::uint64_t tile_rays = 0, tile_samples = 0;
                  const auto x0 = std::size_t(tile.cols().begin());
                  for (int y = tile.rows().begin(); y < tile.rows().end(); ++y) {
                    const std::size_t row = std::size_t(y) * std::size_t(settings.width) + x0;
                    tile_samples += advance_pixels(
                        ctx, tile.cols().size(), [&](std::size_t k) { return row + k; },
                        [&](std::size_t) { return samples; }, pixels, tile_rays);
                  }
                  count_work(tile_rays, tile_samples, rays, progress);
                });
  return rays.load();
}

// A pass over a list of pixels (raster order), each brought to its entry of `targets`
// (film-sized): adaptive sampling's rounds, where few pixels may remain and tiles would
// leave threads idle. `may_skip` is asked before each group of pixels, and again after every
// kSamplesPerStep samples of a pixel (a pixel may be given millions), so a stop request or a
// deadline is honoured within a fraction of a second; once it returns true the rest keep their
// counts (a pixel part of the way to its target continues from there: sums are exact, so the
// steps never change the image). Returns the rays traced.
template <typename Accel>
std::uint64_t render_pixel_list(const RenderContext<Accel>& ctx,
                                const std::vector<std::size_t>& list,
                                const std::vector<std::uint32_t>& targets,
                                PixelAccumulators& pixels, RenderProgress* progress,
                                const std::function<bool()>& may_skip) {
  constexpr std::size_t kPixelsPerTask = 8;
  constexpr std::uint32_t kSamplesPerStep = 4096;
  std::atomic<std::uint64_t> rays{0};
  parallel_over(ctx.settings, tbb::blocked_range<std::size_t>(0, list.size(), kPixelsPerTask),
                [&](const tbb::blocked_range<std::size_t>& part) {
                  for (bool more = true; more;) {
                    if (may_skip()) return;
                    more = false;
                    const auto step_target = [&](std::size_t p) {
                      const std::uint32_t from = pixels.samples[p];
                      if (targets[p] <= from || targets[p] - from <= kSamplesPerStep) {
                        return targets[p];
                      }
                      more = true;
                      return from + kSamplesPerStep;
                    };
                    std::uint64_t part_rays = 0;
                    const std::uint64_t part_samples = advance_pixels(
                        ctx, part.size(), [&](std::size_t k) { return list[part.begin() + k]; },
                        step_target, pixels, part_rays);
                    count_work(part_rays, part_samples, rays, progress);
                  }
                });
  return rays.load();
}

// Renders every pixel of `film` (already sized) at `samples_per_pixel` in one pass and returns
// the number of rays traced.
template <typename Accel>
std::uint64_t render_tiles(const RenderContext<Accel>& ctx, std::uint32_t samples_per_pixel,
                           Film& film, RenderProgress* progress) {
  const RenderSettings& settings = ctx.settings;
  PixelAccumulators pixels(std::size_t(settings.width) * std::size_t(settings.height),
                           settings.passes.any());
  const std::uint32_t n = samples_per_pixel;
  const std::uint64_t rays = render_pass(ctx, n, pixels, progress);
  resolve(pixels.sums.color, n, film);
  return rays;
}

}  // namespace rtiow
