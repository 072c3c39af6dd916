// Micro-benchmarks (Google Benchmark): the sphere test, one rtcIntersect1 on the cover
// scene, one scatter of each material, loading a scene file of N spheres and denoising a
// render. Not part of the test run:
//   build/bin/rtiow_microbench --benchmark_repetitions=5 --benchmark_report_aggregates_only

#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/accel/embree_accel.h"
#include "core/accel/naive_accel.h"
#include "core/denoise/denoiser.h"
#include "core/geometry/sphere_intersect.h"
#include "core/render/denoised_output.h"
#include "core/render/render.h"
#include "core/sampling/sampler.h"
#include "core/sampling/sampling.h"
#include "core/scene/builtin_scenes.h"
#include "core/scene_file/scene_file.h"
#include "materials/material.h"

namespace rtiow {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Random rays from around the cover's camera towards the scene: a realistic mix of hits
// and misses.
std::vector<Ray> cover_like_rays(std::size_t count) {
  Pcg32 rng(9, 9);
  std::vector<Ray> rays;
  rays.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 origin{13.0f + rng.next_float(), 2.0f + rng.next_float(), 3.0f + rng.next_float()};
    const Vec3 target{-6 + 12 * rng.next_float(), 2 * rng.next_float(), -6 + 12 * rng.next_float()};
    rays.push_back(Ray{origin, normalize(target - origin)});
  }
  return rays;
}

void BM_SphereTest(benchmark::State& state) {
  const auto rays = cover_like_rays(1024);
  const Vec3 center{0, 1, 0};
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(sphere_hit_distance(center, 1.0f, rays[i++ & 1023], 0.0f, kInf));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SphereTest);

// One closest-hit query on the cover scene: rtcIntersect1 for EmbreeAccel, the vectorised
// loop over all 485 spheres for NaiveAccel.
template <typename Accel>
void BM_IntersectCover(benchmark::State& state) {
  const Scene scene = make_builtin_scene("cover", 1);
  const Accel accel(scene.spheres);
  const auto rays = cover_like_rays(4096);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(accel.intersect(rays[i++ & 4095], kInf));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_IntersectCover<EmbreeAccel>);
BENCHMARK(BM_IntersectCover<NaiveAccel>);

template <typename M>
void BM_Scatter(benchmark::State& state, M material) {
  const Material m = material;
  SurfaceHit hit{};
  hit.normal = {0, 1, 0};
  hit.front_face = true;
  const Vec3 in = normalize(Vec3{0.3f, -1.0f, 0.1f});
  SampleStream rng(1, 2, 3, 4);
  for (auto _ : state) benchmark::DoNotOptimize(scatter(m, in, hit, rng.next_bounce()));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK_CAPTURE(BM_Scatter, lambertian, Lambertian{{0.5f, 0.5f, 0.5f}});
BENCHMARK_CAPTURE(BM_Scatter, metal_fuzz_0_3, make_metal({0.8f, 0.8f, 0.8f}, 0.3f));
BENCHMARK_CAPTURE(BM_Scatter, dielectric, Dielectric{1.5f});

// Loading a file of `spheres:N` (as `rtiow scene spheres:N` writes it, a material per
// sphere): the streaming parse, the material names and the scene's validation.
void BM_LoadSceneFile(benchmark::State& state) {
  const auto spheres = std::size_t(state.range(0));
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("rtiow_bench_spheres_" + std::to_string(spheres) + ".json");
  {
    std::ofstream out(path, std::ios::binary);
    out << scene_to_json(make_builtin_scene("spheres:" + std::to_string(spheres), 1));
  }
  const auto bytes = std::filesystem::file_size(path);
  for (auto _ : state) benchmark::DoNotOptimize(load_scene_file(path.string()));
  std::filesystem::remove(path);
  state.SetBytesProcessed(std::int64_t(state.iterations() * bytes));
  state.counters["spheres"] = double(spheres);
}
BENCHMARK(BM_LoadSceneFile)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// The denoiser on the cover at 400x267 and 8 spp, rendered once: the time the denoiser adds
// to a render, reported per megapixel (the render's own time is not in it).
void BM_DenoiseCover(benchmark::State& state) {
  const Scene scene = make_builtin_scene("cover", kDefaultSceneSeed);
  RenderSettings settings;
  settings.width = 400, settings.height = 267, settings.samples = FixedSamples{8};
  settings.estimate_error = true, settings.passes = {true, true, true};
  const DenoiseInput input = denoise_input(render(scene, settings));
  for (auto _ : state) benchmark::DoNotOptimize(denoise(input));
  const double megapixels = double(input.size()) * 1e-6;
  state.counters["s_per_megapixel"] =
      benchmark::Counter(double(state.iterations()) * megapixels,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_DenoiseCover)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace rtiow

BENCHMARK_MAIN();
