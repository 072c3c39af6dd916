#include "app/measure/bench_command.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/measure/quick_run.h"
#include "app/source_commit.h"
#include "core/measure/bench_compare.h"
#include "core/measure/bench_runs.h"
#include "core/render/render_settings.h"
#include "core/sampling/sampler.h"

namespace rtiow {
namespace {

CLI::App* add_bench_options(CLI::App& app, BenchOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "bench",
      "Measure Embree against the naive loop: cover scene, scaling to 1M spheres, raw "
      "rtcIntersect1 rate and traversal alone, thread scaling, each after a warm-up run; prints a "
      "table with each figure's median and range, writes JSON (with the machine and build), a "
      "CSV of every run and a PNG plot (about 2 minutes on a 2-core machine; --quick: a few "
      "seconds)");
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
  cmd->add_option("--repeat", o.repeat,
                  "Timed runs per measurement, after one warm-up run; the median and the range "
                  "are reported")
      ->capture_default_str();
  cmd->add_option("--threads", o.threads, "Worker threads (0: all cores)")->capture_default_str();
  cmd->add_option("--out", o.out_dir, "Directory for bench.json, bench.csv and bench.png")
      ->capture_default_str();
  cmd->add_option("--summary-json", o.summary_json,
                  "Also write the headline figures as JSON here, for scripts (the schema every "
                  "command's summary shares: docs/usage.md)");
  cmd->add_option("--compare", o.compare,
                  "Measure nothing: compare two bench.json files (two commits or machines) "
                  "figure by figure, saying which differ beyond the noise (their runs' ranges "
                  "apart)")
      ->expected(2)
      ->type_name("A.json B.json");
  cmd->add_flag("--quick", o.quick,
                "A short run for a first look: a 200x112 cover at 4 spp, up to 10^4 spheres, "
                "one run each (options given still apply)");
  return cmd;
}

CLI::App* add_point_options(CLI::App& app, PointOptions& o) {
  // bench runs each scaling point in a process of its own, through this command; it is hidden
  // from rtiow --help (a user runs bench), but its own help is true.
  CLI::App* point_cmd = app.add_subcommand(
      "bench-point",
      "One scaling point of rtiow bench, in a process of its own: renders a scene with one "
      "intersector and prints its figures as JSON on one line");
  point_cmd->group("");  // hidden from --help
  point_cmd->add_option("--scene", o.scene, "Built-in scene (e.g. spheres:100000)")->required();
  point_cmd->add_option("--accel", o.accel, "Intersector: embree or naive")->capture_default_str();
  point_cmd->add_option("--width", o.width, "Image width")->capture_default_str();
  point_cmd->add_option("--height", o.height, "Image height")->capture_default_str();
  point_cmd->add_option("--spp", o.spp, "Samples per pixel")->capture_default_str();
  point_cmd->add_option("--depth", o.depth, "Maximum rays per path")->capture_default_str();
  point_cmd->add_option("--repeat", o.repeat, "Renders to time, at most (the median is reported)")
      ->capture_default_str();
  point_cmd->add_option("--threads", o.threads, "Worker threads (0: all cores)")
      ->capture_default_str();
  point_cmd->add_option("--budget", o.budget, "Seconds after which no further repeat starts")
      ->capture_default_str();
  point_cmd
      ->add_option("--roulette", o.roulette,
                   "Russian roulette: on (rtiow's default) or off (every path to --depth, the "
                   "paths of the book's program and of the lean tracer, for a per-ray comparison)")
      ->check(CLI::IsMember({roulette_name(true), roulette_name(false)}))
      ->capture_default_str();
  point_cmd
      ->add_option("--sampler", o.sampler,
                   "Sampler: independent (the book's, as the lean tracer draws), sobol "
                   "(rtiow render's default: the loop of the command with its defaults) or "
                   "padded-sobol")
      ->check(CLI::IsMember(sampler_name_list()))
      ->capture_default_str();
  point_cmd->add_flag("--helper", o.helper,
                      "Started by rtiow bench, which reports a signal: end on one without a word");
  return point_cmd;
}

// `rtiow bench-point` with the point's options: this program, run again for one point.
std::vector<std::string> point_command(const PointOptions& p) {
  const std::string exe = std::filesystem::read_symlink("/proc/self/exe").string();
  std::vector<std::string> argv{exe,         "bench-point",
                                "--scene",   p.scene,
                                "--accel",   p.accel,
                                "--width",   std::to_string(p.width),
                                "--height",  std::to_string(p.height),
                                "--spp",     std::to_string(p.spp),
                                "--depth",   std::to_string(p.depth),
                                "--repeat",  std::to_string(p.repeat),
                                "--threads", std::to_string(p.threads),
                                "--budget",  std::to_string(p.budget)};
  if (p.helper) argv.push_back("--helper");
  return argv;
}

}  // namespace

std::function<int()> add_bench_command(CLI::App& app) {
  auto options = std::make_shared<BenchOptions>();
  options->commit = source_commit();
  options->point_command = point_command;
  CLI::App* cmd = add_bench_options(app, *options);
  auto point = std::make_shared<PointOptions>();
  CLI::App* point_cmd = add_point_options(app, *point);
  return [options, point, cmd, point_cmd] {
    if (cmd->parsed()) {
      if (!options->compare.empty()) {
        return compare_bench_files(options->compare[0], options->compare[1]);
      }
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
    if (point_cmd->parsed()) return run_point(*point);  // --helper: main read it first
    return -1;
  };
}

}  // namespace rtiow
