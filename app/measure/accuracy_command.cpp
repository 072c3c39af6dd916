#include "app/measure/accuracy_command.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/cli_checks.h"
#include "app/measure/quick_run.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/measure/accuracy_options.h"
#include "core/measure/accuracy_study.h"

namespace rtiow {
namespace {

// Every option checked before the reference (minutes of rendering) is made. The sample
// counts' limits depend on each other, so every one broken is named in the one line.
void check_options(const AccuracyOptions& o) {
  if (o.width < 1) throw InvalidInput("--width must be >= 1");
  std::vector<std::string> spp_problems;
  if (o.max_spp < 64) {
    spp_problems.push_back("--max-spp must be >= 64 (the fits and the budget sweep start at " +
                           std::string("16-32), got ") + std::to_string(o.max_spp));
  }
  if (std::int64_t(o.reference_spp) < 4 * std::int64_t(std::max(o.max_spp, 64))) {
    spp_problems.push_back("--reference-spp must be at least 4x --max-spp (" +
                           std::to_string(4 * std::int64_t(std::max(o.max_spp, 64))) +
                           ", or its noise swamps the errors), got " +
                           std::to_string(o.reference_spp));
  }
  if (o.fixed_spp < 2) {
    spp_problems.push_back("--fixed-spp must be >= 2, got " + std::to_string(o.fixed_spp));
  }
  if (o.book_spp < 16) {
    spp_problems.push_back("--book-spp must be >= 16, got " + std::to_string(o.book_spp));
  }
  if (!spp_problems.empty()) {
    std::string text;
    for (const std::string& p : spp_problems) text += (text.empty() ? "" : "; ") + p;
    throw InvalidInput(text);
  }
  // The two directories: missing ones are made, but a path that is a file is refused.
  check_output_directory(o.out_dir, "--out");
  if (!o.cache_dir.empty()) check_output_directory(o.cache_dir, "--cache-dir");
  if (o.repeat < 1) throw InvalidInput("--repeat must be >= 1");
  if (o.depths.empty() || *std::min_element(o.depths.begin(), o.depths.end()) < 1) {
    throw InvalidInput("--depths must list depth limits >= 1");
  }
  for (const double e : o.target_errors) {
    if (!(e > 0) || !std::isfinite(e)) throw InvalidInput("--target-errors must be > 0");
  }
  for (const double e : o.image_errors) {
    if (!(e > 0) || !std::isfinite(e)) throw InvalidInput("--image-errors must be > 0");
  }
}

// What is swept: the scene, its size, the sample counts and the settings compared.
void add_sweep_options(CLI::App* cmd, AccuracyOptions& o) {
  cmd->add_option("--scene", o.scene, "Built-in scene")->capture_default_str();
  cmd->add_option("--scene-seed", o.scene_seed, "Seed of the scene's random layout")
      ->check(kNotNegative)
      ->capture_default_str();
  cmd->add_option("--width", o.width, "Image width (height from the scene's aspect ratio)")
      ->capture_default_str();
  cmd->add_option("--reference-spp", o.reference_spp,
                  "Samples per pixel of the reference, at least 4x --max-spp")
      ->capture_default_str();
  cmd->add_option("--max-spp", o.max_spp,
                  "Largest spp of the sweep (1, 2, 4, ... up to it), at least 64")
      ->capture_default_str();
  cmd->add_option("--fixed-spp", o.fixed_spp,
                  "Spp of the depth and intersector comparisons (Fresnel: 4x this), at least 2")
      ->capture_default_str();
  cmd->add_option("--depths", o.depths, "Depth limits to compare")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--target-errors", o.target_errors, "Adaptive sampling targets to compare")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--image-errors", o.image_errors, "Image errors (--image-error) to compare")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--book-spp", o.book_spp,
                  "The spp whose independent-sampling error is the goal of the time-to-quality "
                  "headline (the book's final render: 500), at least 16")
      ->capture_default_str();
}

// How the measurements run and where their figures go.
void add_run_options(CLI::App* cmd, AccuracyOptions& o) {
  cmd->add_option("--seed", o.seed, "Seed of the measured renders")
      ->check(kNotNegative)
      ->capture_default_str();
  cmd->add_option("--threads", o.threads, "Worker threads (0: all cores)")->capture_default_str();
  cmd->add_option("--repeat", o.repeat,
                  "Renders per measurement; the median time is kept (the image is the same)")
      ->capture_default_str();
  cmd->add_option("--out", o.out_dir, "Directory for accuracy.json, accuracy.csv, accuracy.png")
      ->capture_default_str();
  cmd->add_option("--cache-dir", o.cache_dir,
                  "Where references are kept (default: $XDG_CACHE_HOME/rtiow or ~/.cache/rtiow)");
  cmd->add_option("--summary-json", o.summary_json,
                  "Also write the headline figures as JSON here, for scripts (the schema every "
                  "command's summary shares: docs/usage.md)");
  cmd->add_flag("-q,--quiet", o.quiet, "No progress on stderr");
  cmd->add_flag("--quick", o.quick,
                "A short run for a first look: 80 px wide, a reference of 1024 spp, spp up to "
                "256, fewer depths and targets, one run each (options given still apply)");
}

}  // namespace

std::function<int()> add_accuracy_command(CLI::App& app) {
  auto options = std::make_shared<AccuracyOptions>();
  AccuracyOptions& o = *options;
  CLI::App* cmd = app.add_subcommand(
      "accuracy",
      "Measure speed against accuracy on a scene: error against a cached high-spp reference "
      "for spp 1..N with each sampler, adaptive sampling (budget, image error, target error), "
      "the time to the book's quality (against the book's estimator: independent sampling "
      "without Russian roulette), the depth limit, the intersector and the Fresnel "
      "model; prints tables, writes JSON, CSV and a PNG plot (about 2 minutes on a 2-core "
      "machine, the reference cached after the first run; --quick: a few seconds)");
  add_sweep_options(cmd, o);
  add_run_options(cmd, o);
  return [options, cmd] {
    if (!cmd->parsed()) return -1;
    if (options->quick) {
      apply_quick_run(*cmd, {{"--width", "80"},
                             {"--reference-spp", "1024"},
                             {"--max-spp", "256"},
                             {"--fixed-spp", "16"},
                             {"--book-spp", "64"},
                             {"--depths", "1,2,4,8,50"},
                             {"--target-errors", "0.2,0.1"},
                             {"--image-errors", "0.1,0.05"},
                             {"--repeat", "1"}});
    }
    check_options(*options);
    return run_accuracy(*options);
  };
}

}  // namespace rtiow
