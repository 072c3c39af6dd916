#include "app/measure/bench_command.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "app/child_process.h"
#include "app/measure/bench_report.h"
#include "app/measure/figure_outputs.h"
#include "app/measure/measure_summary.h"
#include "app/measure/quick_run.h"
#include "app/measure/trace_rate.h"
#include "core/io/atomic_file.h"
#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/render/render.h"
#include "core/render/render_request.h"
#include "core/scene/builtin_scenes.h"

namespace rtiow {
namespace {

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

struct BenchOptions {
  int width = 400, height = 225, spp = 8, depth = 20;
  int scaling_width = 400, scaling_height = 225, scaling_spp = 4, scaling_depth = 8;
  std::uint64_t max_spheres = 1'000'000;
  double naive_budget = 60.0;
  int repeat = 3;
  int threads = 0;
  std::string out_dir = "bench";  // bench.json and bench.png
  std::string summary_json;       // empty: none
  bool quick = false;
};

struct PointOptions {
  std::string scene;
  std::string accel = "embree";
  int width = 400, height = 225, spp = 2, depth = 8, repeat = 3, threads = 0;
  double budget = 60.0;
  std::string roulette = roulette_name(true);  // off: the book's (and the lean tracer's) paths
  std::string sampler = to_string(SamplerKind::Independent);  // the book's; sobol: render's
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int all_threads(int threads) {
  return threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
}

// Resident memory now (VmRSS), to separate the shared libraries mapped at start-up
// (OpenImageIO alone brings in some 250) from what a scene and its BVH cost.
double current_rss_mb() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      double kib = 0;
      status >> kib;
      return kib / 1024.0;
    }
  }
  return 0.0;
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
}

// Renders `repeat` times (fewer once `budget` seconds are spent) and reports medians.
json measure_render(const Scene& scene, RenderSettings settings, int repeat, double budget) {
  std::vector<double> build, seconds;
  std::uint64_t rays = 0;
  double spent = 0.0;
  for (int i = 0; i < repeat && (i == 0 || spent < budget); ++i) {
    const RenderResult r = render(scene, settings);
    build.push_back(r.build_seconds);
    seconds.push_back(r.render_seconds);
    rays = r.rays_traced;
    spent += r.build_seconds + r.render_seconds;
  }
  const double s = median(seconds);
  return {{"accelerator", to_string(settings.accel)},
          {"threads", all_threads(settings.threads)},
          {"runs", seconds.size()},
          {"build_seconds", median(build)},
          {"render_seconds", s},
          {"rays", rays},
          {"mrays_per_second", double(rays) / s * 1e-6}};
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
  std::printf("%s\n", result.dump().c_str());
  return 0;
}

// Runs one scaling point in a child process and returns its JSON line.
json run_point_in_child(const BenchOptions& o, std::uint64_t spheres, const std::string& accel,
                        double budget) {
  const std::string exe = std::filesystem::read_symlink("/proc/self/exe").string();
  const std::vector<std::string> argv{exe,         "bench-point",
                                      "--scene",   "spheres:" + std::to_string(spheres),
                                      "--accel",   accel,
                                      "--width",   std::to_string(o.scaling_width),
                                      "--height",  std::to_string(o.scaling_height),
                                      "--spp",     std::to_string(o.scaling_spp),
                                      "--depth",   std::to_string(o.scaling_depth),
                                      "--repeat",  std::to_string(o.repeat),
                                      "--threads", std::to_string(o.threads),
                                      "--budget",  std::to_string(budget)};
  const ChildRun run = run_child(argv);
  if (!run.ok()) {
    const std::string why = !run.started ? run.failure
                            : run.signal ? "ended by signal " + std::to_string(run.signal)
                                         : "exit status " + std::to_string(run.exit_code);
    throw std::runtime_error("bench: the point spheres:" + std::to_string(spheres) + " with " +
                             accel + " failed (" + why + ")");
  }
  return json::parse(run.output);
}

json bench_cover(const BenchOptions& o) {
  auto [scene, settings] = book_job(make_builtin_scene("cover", kDefaultSceneSeed), o.width,
                                    o.height, o.spp, o.depth, o.threads, AccelKind::Embree);

  json cover = {{"scene", "cover"}, {"spheres", scene.spheres.size()},
                {"width", o.width}, {"height", o.height},
                {"spp", o.spp},     {"depth", o.depth}};
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
  std::vector<double> rates, traversal_rates;
  for (int i = 0; i < o.repeat; ++i) {
    rates.push_back(measure_trace_rate(scene, rays, o.threads).mrays_per_second());
    traversal_rates.push_back(
        measure_trace_rate(scene, rays, o.threads, EmbreeCallback::Nothing).mrays_per_second());
  }
  cover["trace"] = {{"rays", rays.size()},
                    {"threads", all_threads(o.threads)},
                    {"mrays_per_second", median(rates)}};
  // The same rays with a callback that returns at once: Embree's traversal and calls alone
  // (no hit ever shortens a ray, so this is an upper bound on what the traversal costs).
  cover["traversal"] = {{"rays", rays.size()},
                        {"threads", all_threads(o.threads)},
                        {"mrays_per_second", median(traversal_rates)}};
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

int run_bench(const BenchOptions& o) {
  if (o.repeat < 1) throw InvalidInput("--repeat must be >= 1");
  if (o.naive_budget <= 0) throw InvalidInput("--naive-budget must be > 0");
  if (o.max_spheres < 10) throw InvalidInput("--max-spheres must be >= 10");
  // The cover's settings checked before any work.
  book_job(make_builtin_scene("cover", kDefaultSceneSeed), o.width, o.height, o.spp, o.depth,
           o.threads, AccelKind::Embree);

  json results = {{"threads", all_threads(o.threads)},
                  {"repeat", o.repeat},
                  {"scaling_settings",
                   {{"width", o.scaling_width},
                    {"height", o.scaling_height},
                    {"spp", o.scaling_spp},
                    {"depth", o.scaling_depth},
                    {"naive_budget_seconds", o.naive_budget}}}};
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<OutputClaim> summary = claim_summary(o.summary_json);
  const FigureOutputs outputs(o.out_dir, {"bench.json", "bench.png"}, "--out");
  const std::string json_path = outputs.path("bench.json");
  results["cover"] = bench_cover(o);
  results["scaling"] = bench_scaling(o);

  print_bench_table(results);
  write_bench_json(results, json_path);
  std::printf("\nfigures: %s\n", one_line(json_path).c_str());
  const bool plotted = plot_bench(results, outputs.path("bench.png"));
  if (summary) {
    const std::chrono::duration<double> seconds = std::chrono::steady_clock::now() - start;
    const MeasureFiles files{json_path, "", plotted ? outputs.path("bench.png") : ""};
    write_text_atomically(o.summary_json, bench_summary_json(results, files, seconds.count()));
  }
  return 0;
}

}  // namespace

std::function<int()> add_bench_command(CLI::App& app) {
  auto options = std::make_shared<BenchOptions>();
  BenchOptions& o = *options;
  CLI::App* cmd = app.add_subcommand(
      "bench",
      "Measure Embree against the naive loop: cover scene, scaling to 1M spheres, raw "
      "rtcIntersect1 rate and traversal alone, thread scaling; prints a table, writes JSON and a "
      "PNG plot (about 100 s on a 2-core machine; --quick: a few seconds)");
  cmd->add_option("--width", o.width, "Cover scene width")->capture_default_str();
  cmd->add_option("--height", o.height, "Cover scene height")->capture_default_str();
  cmd->add_option("--spp", o.spp, "Cover scene samples per pixel")->capture_default_str();
  cmd->add_option("--depth", o.depth, "Cover scene depth")->capture_default_str();
  cmd->add_option("--scaling-width", o.scaling_width, "spheres:N width")->capture_default_str();
  cmd->add_option("--scaling-height", o.scaling_height, "spheres:N height")->capture_default_str();
  cmd->add_option("--scaling-spp", o.scaling_spp, "spheres:N samples per pixel")
      ->capture_default_str();
  cmd->add_option("--scaling-depth", o.scaling_depth, "spheres:N depth")->capture_default_str();
  cmd->add_option("--max-spheres", o.max_spheres, "Largest N of the series 10, 100, ...")
      ->capture_default_str();
  cmd->add_option("--naive-budget", o.naive_budget,
                  "Seconds one naive render may take; larger N are skipped")
      ->capture_default_str();
  cmd->add_option("--repeat", o.repeat, "Runs per measurement; the median is reported")
      ->capture_default_str();
  cmd->add_option("--threads", o.threads, "Worker threads (0: all cores)")->capture_default_str();
  cmd->add_option("--out", o.out_dir, "Directory for bench.json and bench.png")
      ->capture_default_str();
  cmd->add_option("--summary-json", o.summary_json,
                  "Also write the headline figures as JSON here, for scripts (the schema every "
                  "command's summary shares: docs/usage.md)");
  cmd->add_flag("--quick", o.quick,
                "A short run for a first look: a 200x112 cover at 4 spp, up to 10^4 spheres, "
                "one run each (options given still apply)");

  auto point = std::make_shared<PointOptions>();
  // bench runs each scaling point in a process of its own, through this command; it is hidden
  // from rtiow --help (a user runs bench), but its own help is true.
  CLI::App* point_cmd = app.add_subcommand(
      "bench-point",
      "One scaling point of rtiow bench, in a process of its own: renders a scene with one "
      "intersector and prints its figures as JSON on one line");
  point_cmd->group("");  // hidden from --help
  point_cmd->add_option("--scene", point->scene, "Built-in scene (e.g. spheres:100000)")
      ->required();
  point_cmd->add_option("--accel", point->accel, "Intersector: embree or naive")
      ->capture_default_str();
  point_cmd->add_option("--width", point->width, "Image width")->capture_default_str();
  point_cmd->add_option("--height", point->height, "Image height")->capture_default_str();
  point_cmd->add_option("--spp", point->spp, "Samples per pixel")->capture_default_str();
  point_cmd->add_option("--depth", point->depth, "Maximum rays per path")->capture_default_str();
  point_cmd
      ->add_option("--repeat", point->repeat, "Renders to time, at most (the median is reported)")
      ->capture_default_str();
  point_cmd->add_option("--threads", point->threads, "Worker threads (0: all cores)")
      ->capture_default_str();
  point_cmd->add_option("--budget", point->budget, "Seconds after which no further repeat starts")
      ->capture_default_str();
  point_cmd
      ->add_option("--roulette", point->roulette,
                   "Russian roulette: on (rtiow's default) or off (every path to --depth, the "
                   "paths of the book's program and of the lean tracer, for a per-ray comparison)")
      ->check(CLI::IsMember({roulette_name(true), roulette_name(false)}))
      ->capture_default_str();
  point_cmd
      ->add_option("--sampler", point->sampler,
                   "Sampler: independent (the book's, as the lean tracer draws), sobol "
                   "(rtiow render's default: the loop of the command with its defaults) or "
                   "padded-sobol")
      ->check(CLI::IsMember(sampler_name_list()))
      ->capture_default_str();

  return [options, point, cmd, point_cmd] {
    if (cmd->parsed()) {
      if (options->quick) {
        apply_quick_run(*cmd, {{"--width", "200"},
                               {"--height", "112"},
                               {"--spp", "4"},
                               {"--scaling-width", "200"},
                               {"--scaling-height", "112"},
                               {"--max-spheres", "10000"},
                               {"--naive-budget", "5"},
                               {"--repeat", "1"}});
      }
      return run_bench(*options);
    }
    if (point_cmd->parsed()) return run_point(*point);
    return -1;
  };
}

}  // namespace rtiow
