#include "core/measure/bench_runs.h"
#include "core/limits/setting_name.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/io/child_process.h"
#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/measure/bench_compare.h"
#include "core/measure/bench_report.h"
#include "core/measure/figure_outputs.h"
#include "core/measure/figures.h"
#include "core/measure/measure_summary.h"
#include "core/measure/trace_rate.h"
#include "core/parallel/thread_count.h"
#include "core/render/render.h"
#include "core/render/render_request.h"
#include "core/scene/builtin_scenes.h"
#include "core/version.h"

namespace rtiow {
namespace {

using json = Figures;
using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A rate's median and spread over runs: "mrays_per_second" (the median, as every reader of
// bench.json takes it), "_min", "_max" and "_mad", the median absolute deviation from the
// median (Google Benchmark's and hyperfine's robust spread: one slow run moves it little).
void put_spread(json& into, const std::string& key, const std::vector<double>& values) {
  const double middle = median(values);
  std::vector<double> deviations;
  for (const double v : values) deviations.push_back(std::abs(v - middle));
  into[key] = middle;
  into[key + "_min"] = *std::min_element(values.begin(), values.end());
  into[key + "_max"] = *std::max_element(values.begin(), values.end());
  into[key + "_mad"] = median(deviations);
}

// A figure of /proc/self/status in MB ("VmRSS:", "VmHWM:"), 0 where absent.
double status_mb(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == field) {
      double kib = 0;
      status >> kib;
      return kib / 1024.0;
    }
  }
  return 0.0;
}

// Resident memory now, to separate the shared libraries mapped at start-up (OpenImageIO alone
// brings in some 250) from what a scene and its BVH cost.
double current_rss_mb() {
  return status_mb("VmRSS:");
}

// This process's own peak: its memory's high-water mark. Not getrusage's ru_maxrss, which a
// spawned child inherits from the parent at exec (the parent's peak, 153 MB after the cover's
// recorded rays, showed as every scaling point's).
double peak_rss_mb() {
  return status_mb("VmHWM:");
}

// Renders once untimed at 1 spp, the warm-up (the first configuration measured paid for the
// thread pool's start, the film's first page faults and cold caches, and read 1.4-4.1 against
// 6.4-10.3 Mrays/s for the same configuration timed after it), then `repeat` times (fewer once
// `budget` seconds are spent): each run, and the median, least and most of each figure.
json measure_render(const Scene& scene, RenderSettings settings, int repeat, double budget) {
  double warmup_seconds = 0.0;
  {  // its film gone before the timed runs, which would otherwise count it in their peak memory
    RenderSettings warm = settings;
    warm.samples = FixedSamples{1};
    const RenderResult warm_up = render(scene, warm);
    warmup_seconds = warm_up.build_seconds + warm_up.render_seconds;
  }
  std::vector<double> build, seconds, rates;
  json each = json::array();
  std::uint64_t rays = 0;
  double spent = warmup_seconds;
  for (int i = 0; i < repeat && (i == 0 || spent < budget); ++i) {
    const RenderResult r = render(scene, settings);
    build.push_back(r.build_seconds);
    seconds.push_back(r.render_seconds);
    rays = r.rays_traced;
    rates.push_back(tracing_mrays_per_second(r));
    each.push_back({{"build_seconds", r.build_seconds},
                    {"render_seconds", r.render_seconds},
                    {"rays", r.rays_traced},
                    {"mrays_per_second", rates.back()}});
    spent += r.build_seconds + r.render_seconds;
  }
  json figures = {{"accelerator", to_string(settings.accel)},
                  {"threads", thread_count(settings.threads)},
                  {"sampler", to_string(settings.sampler)},
                  {"seed", settings.seed},
                  {"warmup_seconds", warmup_seconds},
                  {"runs", seconds.size()},
                  {"rays", rays}};
  put_spread(figures, "build_seconds", build);
  put_spread(figures, "render_seconds", seconds);
  put_spread(figures, "mrays_per_second", rates);
  figures["each_run"] = std::move(each);
  return figures;
}

// The raw trace rate of `rays` as measure_render times a render: a warm-up, then `repeat`
// timed runs with their spread.
json measure_trace(const Scene& scene, const std::vector<Ray>& rays, int threads, int repeat,
                   EmbreeCallback callback) {
  measure_trace_rate(scene, rays, threads, callback);  // the warm-up
  std::vector<double> rates;
  json each = json::array();
  for (int i = 0; i < repeat; ++i) {
    rates.push_back(measure_trace_rate(scene, rays, threads, callback).mrays_per_second());
    each.push_back({{"mrays_per_second", rates.back()}});
  }
  json figures = {
      {"rays", rays.size()}, {"threads", thread_count(threads)}, {"runs", rates.size()}};
  put_spread(figures, "mrays_per_second", rates);
  figures["each_run"] = std::move(each);
  return figures;
}

// The book's job as measured: seed 0, its independent sampler and rtiow's Russian roulette
// unless told otherwise.
ResolvedRender book_job(Scene scene, int width, int height, int spp, int depth, int threads,
                        AccelKind accel, bool russian_roulette = true,
                        SamplerKind sampler = SamplerKind::Independent) {
  RenderRequest r;
  r.width = width, r.height = height, r.spp = spp, r.max_depth = depth;
  r.threads = threads, r.accel = accel;
  r.seed = 0, r.sampler = sampler;
  r.russian_roulette = russian_roulette;
  return resolve(std::move(scene), r);
}

// Runs one scaling point in a child process and returns its JSON line.
json run_point_in_child(const BenchOptions& o, std::uint64_t spheres, const std::string& accel,
                        double budget) {
  PointOptions point;
  point.scene = "spheres:" + std::to_string(spheres);
  point.accel = accel;
  point.width = o.scaling_width, point.height = o.scaling_height;
  point.spp = o.scaling_spp, point.depth = o.scaling_depth;
  point.repeat = o.repeat, point.threads = o.threads;
  point.budget = budget;
  point.helper = true;
  const ChildRun run = run_child(o.point_command(point));
  if (!run.ok()) {
    const std::string why = !run.started ? run.failure
                            : run.signal ? "ended by signal " + std::to_string(run.signal)
                                         : "exit status " + std::to_string(run.exit_code);
    throw std::runtime_error("bench: the point spheres:" + std::to_string(spheres) + " with " +
                             accel + " failed (" + why + ")");
  }
  return json::parse(run.output);
}

// The figures of the cover that no machine can give: the whole renderer outrunning the bare
// replay of its own rays, or the replay outrunning Embree's traversal alone. Each says which
// and why; a reader is told the run failed rather than shown the figure as a result.
json failed_measurements(const json& cover) {
  json failed = json::array();
  const double render = cover["embree"]["mrays_per_second"];
  const double trace = cover["trace"]["mrays_per_second"];
  const double traversal = cover["traversal"]["mrays_per_second"];
  // `faster` cannot outrun `slower`: where it did, the ratio and why it cannot be.
  const auto impossible = [&](double faster, double slower, const char* ratio, const char* why) {
    if (faster <= slower) return;
    char text[256];
    std::snprintf(text, sizeof text, "%s %.0f%%: %s", ratio, 100.0 * faster / slower, why);
    failed.push_back(text);
  };
  impossible(render, trace, "render / raw trace rate",
             "the whole renderer cannot outrun the bare replay of its own rays");
  impossible(trace, traversal, "raw trace / traversal alone",
             "the sphere test cannot make the traversal faster");
  return failed;
}

json bench_cover(const BenchOptions& o) {
  auto [scene, settings] = book_job(make_builtin_scene("cover", kDefaultSceneSeed), o.width,
                                    o.height, o.spp, o.depth, o.threads, AccelKind::Embree);

  json cover = {{"scene", "cover"},
                {"spheres", scene.spheres.size()},
                {"width", o.width},
                {"height", o.height},
                {"spp", o.spp},
                {"depth", o.depth},
                {"sampler", to_string(settings.sampler)},
                {"seed", settings.seed}};
  std::fprintf(stderr, "bench: cover scene, embree...\n");
  cover["embree"] = measure_render(scene, settings, o.repeat, 1e9);
  std::fprintf(stderr, "bench: cover scene, naive...\n");
  settings.accel = AccelKind::Naive;
  cover["naive"] = measure_render(scene, settings, o.repeat, 1e9);
  std::fprintf(stderr, "bench: cover scene, embree on 1 thread...\n");
  settings.accel = AccelKind::Embree;
  settings.threads = 1;
  cover["embree_1_thread"] = measure_render(scene, settings, o.repeat, 1e9);

  std::fprintf(stderr, "bench: cover scene, raw rtcIntersect1 on the rays the render traced...\n");
  settings.threads = o.threads;
  const std::vector<Ray> rays = record_traced_rays(scene, settings);
  cover["trace"] = measure_trace(scene, rays, o.threads, o.repeat, EmbreeCallback::SphereTest);
  // The same rays with a callback that returns at once: Embree's traversal and calls alone
  // (no hit ever shortens a ray, so this is an upper bound on what the traversal costs).
  cover["traversal"] = measure_trace(scene, rays, o.threads, o.repeat, EmbreeCallback::Nothing);
  cover["failed_measurements"] = failed_measurements(cover);
  return cover;
}

json bench_scaling(const BenchOptions& o) {
  json points = json::array();
  double last_naive_seconds = 0.0;
  std::uint64_t last_naive_spheres = 0;
  bool naive_running = true;
  for (std::uint64_t n = 10; n <= o.max_spheres; n *= 10) {
    json point = {{"n", n}};
    std::fprintf(stderr, "bench: spheres:%llu, embree...\n", (unsigned long long)n);
    point["embree"] = run_point_in_child(o, n, "embree", 1e9);
    if (naive_running && last_naive_spheres > 0) {
      // The naive loop's cost grows linearly with the sphere count.
      const double predicted = last_naive_seconds * double(n + 4) / double(last_naive_spheres);
      if (predicted > o.naive_budget) {
        naive_running = false;
        point["naive_skipped"] = "predicted " + std::to_string(int(predicted)) +
                                 " s per render, over the budget of " +
                                 std::to_string(int(o.naive_budget)) + " s";
      }
    }
    if (naive_running) {
      std::fprintf(stderr, "bench: spheres:%llu, naive...\n", (unsigned long long)n);
      point["naive"] = run_point_in_child(o, n, "naive", o.naive_budget);
      last_naive_seconds = point["naive"]["render_seconds"].get<double>();
      last_naive_spheres = point["naive"]["spheres"].get<std::uint64_t>();
    }
    points.push_back(point);
  }
  return points;
}

// Where and with what the figures were measured: the CPU and its cores, and what this rtiow
// was built with (core/version.h), so that two bench.json files can be told apart.
json bench_context(const std::string& commit) {
  std::string cpu = "unknown";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);) {
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  return {{"cpu", cpu},
          {"logical_cores", std::thread::hardware_concurrency()},
          {"rtiow", version()},
          {"commit", commit},
          {"build", build_facts()}};
}

}  // namespace

int run_point(const PointOptions& o) {
  const double baseline_mb = current_rss_mb();
  const auto scene_start = Clock::now();
  Scene made = make_builtin_scene(o.scene, kDefaultSceneSeed);
  const double scene_seconds = std::chrono::duration<double>(Clock::now() - scene_start).count();
  const auto [scene, settings] =
      book_job(std::move(made), o.width, o.height, o.spp, o.depth, o.threads, parse_accel(o.accel),
               o.roulette == roulette_name(true), parse_sampler(o.sampler));
  json result = measure_render(scene, settings, o.repeat, o.budget);
  result["scene"] = o.scene;
  result["sampler"] = o.sampler;
  result["spheres"] = scene.spheres.size();
  result["scene_seconds"] = scene_seconds;
  result["peak_rss_mb"] = peak_rss_mb();
  result["startup_rss_mb"] = baseline_mb;
  std::printf("%s\n", figures_text(result).c_str());
  return 0;
}

int run_bench(const BenchOptions& o) {
  if (o.repeat < 1) throw InvalidInput(setting("repeat") + " must be >= 1");
  if (o.naive_budget <= 0) throw InvalidInput(setting("naive_budget") + " must be > 0");
  if (o.max_spheres < 10) throw InvalidInput(setting("max_spheres") + " must be >= 10");
  // The cover's settings checked before any work.
  book_job(make_builtin_scene("cover", kDefaultSceneSeed), o.width, o.height, o.spp, o.depth,
           o.threads, AccelKind::Embree);

  json results = {{"context", bench_context(o.commit)},
                  {"threads", thread_count(o.threads)},
                  {"repeat", o.repeat},
                  {"scaling_settings",
                   {{"width", o.scaling_width},
                    {"height", o.scaling_height},
                    {"spp", o.scaling_spp},
                    {"depth", o.scaling_depth},
                    {"naive_budget_seconds", o.naive_budget}}}};
  const std::unique_ptr<OutputClaim> summary = claim_summary(o.summary_json);
  const FigureOutputs outputs(o.out_dir, {"bench.json", "bench.csv", "bench.png"}, setting("out"));
  const std::string json_path = outputs.path("bench.json");
  results["cover"] = bench_cover(o);
  results["scaling"] = bench_scaling(o);

  print_bench_table(results);
  write_bench_json(results, json_path);
  write_bench_csv(results, outputs.path("bench.csv"));
  std::printf("\nfigures: %s\n", one_line(json_path).c_str());
  std::printf("runs:    %s\n", one_line(outputs.path("bench.csv")).c_str());
  const bool plotted = plot_bench(results, outputs.path("bench.png"));
  if (summary) {
    const MeasureFiles files{json_path, outputs.path("bench.csv"),
                             plotted ? outputs.path("bench.png") : ""};
    write_text_atomically(o.summary_json, bench_summary_json(results, files));
  }
  return 0;
}

}  // namespace rtiow
