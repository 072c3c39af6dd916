#include "app/measure/accuracy_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli_checks.h"
#include "app/measure/accuracy_fits.h"
#include "app/measure/accuracy_options.h"
#include "app/measure/accuracy_reference.h"
#include "app/measure/accuracy_report.h"
#include "app/measure/accuracy_runs.h"
#include "app/measure/figure_outputs.h"
#include "app/measure/measure_summary.h"
#include "app/measure/quick_run.h"
#include "core/io/atomic_file.h"
#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/parallel/thread_count.h"
#include "core/render/render.h"
#include "core/render/render_request.h"
#include "core/scene/builtin_scenes.h"

namespace rtiow {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// The seed of the reference: far from the seeds users pick, so the measured renders are
// independent of it.
constexpr std::uint64_t kReferenceSeed = 0x5eed0000acc0ull;

std::string default_cache_dir() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    return (fs::path(xdg) / "rtiow").string();
  }
  if (const char* home = std::getenv("HOME"); home && *home) {
    return (fs::path(home) / ".cache" / "rtiow").string();
  }
  return ".rtiow-cache";
}

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

// The measured renders' request: the scene's depth and aspect ratio at the given width, the
// book's independent sampler (the reference's and the comparisons').
RenderRequest base_request(const AccuracyOptions& o) {
  RenderRequest r;
  r.width = o.width;
  r.threads = o.threads;
  r.seed = o.seed;
  r.sampler = SamplerKind::Independent;
  r.spp = o.reference_spp;
  return r;
}

int run_accuracy(const AccuracyOptions& o) {
  check_options(o);
  const Scene scene = make_builtin_scene(o.scene, o.scene_seed);
  const RenderSettings base = resolve(scene, base_request(o)).settings;
  const std::unique_ptr<OutputClaim> summary = claim_summary(o.summary_json);
  const FigureOutputs outputs(o.out_dir, {"accuracy.json", "accuracy.csv", "accuracy.png"},
                              "--out");
  const std::string cache_dir = o.cache_dir.empty() ? default_cache_dir() : o.cache_dir;

  RenderSettings reference_settings = base;
  reference_settings.seed = kReferenceSeed;
  const Reference reference =
      load_or_render_reference(scene, reference_settings, cache_dir, o.quiet, !o.cache_dir.empty());
  if (!o.quiet && reference.reused) {
    std::fprintf(stderr, "accuracy: reusing the reference %s\n", reference.path.c_str());
  }

  json r = {{"scene", scene.name},
            {"width", base.width},
            {"height", base.height},
            {"depth", base.max_depth},
            {"seed", o.seed},
            {"reference_spp", o.reference_spp},
            {"reference_seed", kReferenceSeed},
            {"reference_path", reference.path},
            {"reference_reused", reference.reused},
            {"fixed_spp", o.fixed_spp},
            {"max_spp", o.max_spp},
            {"repeat", o.repeat},
            {"threads", thread_count(o.threads)}};
  run_sweeps(o, scene, base_request(o), reference.image, r);

  r["summary"] = summarise(r, o);
  print_table(r);
  const MeasureFiles files = write_figures(o, r);
  if (summary) write_text_atomically(o.summary_json, accuracy_summary_json(r, files));
  return 0;
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
    return run_accuracy(*options);
  };
}

}  // namespace rtiow
