#include "core/render.h"

#include <oneapi/tbb/blocked_range2d.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <chrono>
#include <cstdint>

#include "core/camera.h"
#include "core/embree_accel.h"
#include "core/error.h"
#include "core/integrator.h"
#include "core/naive_accel.h"

namespace rtiow {
namespace {

constexpr int kTileSize = 16;
// Beyond this many pixels the film alone would not fit in a machine's memory.
constexpr std::uint64_t kMaxPixels = 1ull << 31;

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

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

template <typename Accel>
void render_tiles(const Scene& scene, const Camera& camera, const Accel& accel,
                  const RenderSettings& settings, Film& film, RenderProgress* progress,
                  std::uint64_t& total_rays) {
  std::atomic<std::uint64_t> rays{0};
  const int threads =
      settings.threads > 0 ? settings.threads : tbb::info::default_concurrency();
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
  total_rays = rays.load();
}

template <typename Accel>
RenderResult render_with(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         RenderProgress* progress) {
  RenderResult result;
  const auto build_start = Clock::now();
  const Accel accel(scene.spheres);
  result.build_seconds = seconds_since(build_start);

  result.film = Film(settings.width, settings.height);
  const auto render_start = Clock::now();
  render_tiles(scene, camera, accel, settings, result.film, progress, result.rays_traced);
  result.render_seconds = seconds_since(render_start);
  return result;
}

}  // namespace

std::string to_string(AccelKind kind) {
  return kind == AccelKind::Embree ? EmbreeAccel::name() : NaiveAccel::name();
}

AccelKind parse_accel(const std::string& name) {
  if (name == EmbreeAccel::name()) return AccelKind::Embree;
  if (name == NaiveAccel::name()) return AccelKind::Naive;
  throw InvalidInput("unknown accelerator '" + name + "' (known: embree, naive)");
}

void validate(const RenderSettings& s) {
  if (s.width <= 0) throw InvalidInput("width must be > 0, got " + std::to_string(s.width));
  if (s.height <= 0) throw InvalidInput("height must be > 0, got " + std::to_string(s.height));
  if (s.samples_per_pixel <= 0) {
    throw InvalidInput("spp must be > 0, got " + std::to_string(s.samples_per_pixel));
  }
  if (s.max_depth < 0) throw InvalidInput("depth must be >= 0, got " + std::to_string(s.max_depth));
  if (s.threads < 0) throw InvalidInput("threads must be >= 0, got " + std::to_string(s.threads));
  if (std::uint64_t(s.width) * std::uint64_t(s.height) > kMaxPixels) {
    throw InvalidInput("image " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                       " has more than 2^31 pixels");
  }
}

RenderResult render(const Scene& scene, const RenderSettings& settings, RenderProgress* progress) {
  validate(settings);
  const Camera camera(scene.camera, settings.width, settings.height);
  switch (settings.accel) {
    case AccelKind::Embree:
      return render_with<EmbreeAccel>(scene, camera, settings, progress);
    case AccelKind::Naive:
      return render_with<NaiveAccel>(scene, camera, settings, progress);
  }
  throw InvalidInput("unknown accelerator");
}

}  // namespace rtiow
