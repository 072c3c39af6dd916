#include "core/measure/trace_rate.h"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/enumerable_thread_specific.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <chrono>
#include <limits>

#include "core/accel/embree_accel.h"
#include "core/parallel/thread_count.h"
#include "core/render/render_loop.h"

namespace rtiow {
namespace {

// Forwards to Embree and keeps a copy of every ray, per thread.
class RecordingAccel {
 public:
  RecordingAccel(const EmbreeAccel& inner, tbb::enumerable_thread_specific<std::vector<Ray>>& log)
      : inner_(inner), log_(log) {}

  std::optional<Hit> intersect(const Ray& ray, float t_max, std::uint32_t skip) const {
    log_.local().push_back(ray);
    return inner_.intersect(ray, t_max, skip);
  }

 private:
  const EmbreeAccel& inner_;
  tbb::enumerable_thread_specific<std::vector<Ray>>& log_;
};

}  // namespace

std::vector<Ray> record_traced_rays(const Scene& scene, const RenderSettings& settings) {
  validate(settings);
  const Camera camera(scene.camera, settings.width, settings.height);
  const EmbreeAccel embree(scene.spheres);
  tbb::enumerable_thread_specific<std::vector<Ray>> log;
  const RecordingAccel recorder(embree, log);
  Film film(settings.width, settings.height);
  const auto samples = std::uint32_t(std::get<FixedSamples>(settings.samples).per_pixel);
  render_tiles(RenderContext<RecordingAccel>{scene, camera, recorder, settings}, samples, film,
               nullptr);
  std::vector<Ray> rays;
  for (const auto& part : log) rays.insert(rays.end(), part.begin(), part.end());
  return rays;
}

TraceRate measure_trace_rate(const Scene& scene, const std::vector<Ray>& rays, int threads,
                             EmbreeCallback callback) {
  const EmbreeAccel embree(scene.spheres, callback);
  std::atomic<std::uint64_t> hits{0};
  const auto start = std::chrono::steady_clock::now();
  with_threads(threads, [&] {  // above the cores too, without TBB's warning
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, rays.size(), 4096),
        [&](const tbb::blocked_range<std::size_t>& range) {
          std::uint64_t local = 0;
          for (std::size_t i = range.begin(); i < range.end(); ++i) {
            local += embree.intersect(rays[i], std::numeric_limits<float>::infinity()).has_value();
          }
          hits += local;
        });
  });
  TraceRate rate;
  rate.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  rate.rays = rays.size();
  rate.hits = hits.load();
  return rate;
}

}  // namespace rtiow
