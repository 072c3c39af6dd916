#include "app/command_line.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app/command_error.h"
#include "app/command_text.h"
#include "core/io/image_output.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/limits/nearest_name.h"
#include "core/limits/number_text.h"
#include "core/render/recorded_request.h"
#include "core/render/render_request.h"

namespace rtiow {
namespace {

// Checks of command-line values with short messages (CLI11's own range checks print the
// whole range of a double, hundreds of digits, in their error line).

// A seed: a whole number from 0 to 2^64-1 (an unsigned option would wrap "-1", and CLI11
// saturates a value beyond 2^64 instead of refusing it).
const CLI::Validator kNotNegative(
    [](std::string& text) -> std::string {
      if (text.find('-') != std::string::npos) return "must not be negative";
      std::uint64_t value = 0;
      const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
      return error == std::errc() && end == text.data() + text.size()
                 ? ""
                 : "must be a whole number from 0 to 2^64-1";
    },
    "NUMBER >= 0");

// A finite number above 0, or at least 0 where `zero` is allowed: "inf" and "nan" are not
// amounts.
CLI::Validator finite_number(bool zero, const std::string& refusal, const std::string& kind) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double value = 0;
        const bool read = CLI::detail::lexical_cast(text, value) && std::isfinite(value);
        return read && (value > 0 || (zero && value == 0)) ? "" : refusal;
      },
      kind);
}

// Time limits, intervals, thresholds.
const CLI::Validator kFiniteNotNegative =
    finite_number(true, "must be a finite number >= 0", "NUMBER >= 0");

// Error targets: 0 would be a target no render reaches, and leaving the option out is how to
// ask for none.
const CLI::Validator kFinitePositive = finite_number(
    false, "must be a finite number > 0 (leave the option out for no error target)", "NUMBER > 0");

// A number from `least` to `most`, the bounds written as the help writes them (CLI11's own
// Range prints "0.000000 to 0.500000" for 1e-12 to 0.5, and only its bounds).
CLI::Validator from_to(double least, double most) {
  const std::string range = shortest_text(least) + " to " + shortest_text(most);
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double value = 0;
        return CLI::detail::lexical_cast(text, value) && value >= least && value <= most
                   ? ""
                   : "must be from " + range + ", got " + text;
      },
      "NUMBER " + range);
}

// A whole number as a user writes it: decimal. CLI11 reads "010" as octal 8 and "0x10" as
// sixteen; every whole-number option takes leading zeros as decimal and refuses another base.
// A transform, so that it runs before the option's own checks and conversion.
const CLI::Validator kDecimal(
    [](std::string& text) -> std::string {
      const std::size_t at = !text.empty() && (text[0] == '+' || text[0] == '-') ? 1 : 0;
      if (text.size() > at + 1 && text[at] == '0' && std::isalpha(std::uint8_t(text[at + 1]))) {
        return "'" + text + "' is not a decimal number";
      }
      std::size_t zeros = at;
      while (zeros + 1 < text.size() && text[zeros] == '0' &&
             std::isdigit(std::uint8_t(text[zeros + 1]))) {
        ++zeros;
      }
      text.erase(at, zeros - at);
      return "";
    },
    "");

// Gives every whole-number option of `app` and its commands kDecimal.
void read_whole_numbers_as_decimal(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    const std::string type = option->get_type_name();
    if (type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0) option->transform(kDecimal);
  }
  for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    read_whole_numbers_as_decimal(*command);
  }
}

// --quick for the measurement commands: a short run of the same measurement, for a first look
// or a check that it works, in seconds to a minute or two rather than many minutes.
// Gives each option of `cmd` that the user did not give the quick run's value ("--repeat",
// "1"), as if it had been typed: the option's own checks apply.
void apply_quick_run(CLI::App& cmd,
                     const std::vector<std::pair<std::string, std::string>>& settings) {
  for (const auto& [name, value] : settings) {
    CLI::Option* option = cmd.get_option(name);
    if (option->count() > 0) continue;
    option->add_result(value);
    option->run_callback();
  }
}

// ---- rtiow render

// The options, in the order --help lists them: what to render, where, how many samples and
// how, how the process runs, and the camera.
CLI::Option* add_scene_options(CLI::App* cmd, RenderOptions& o) {
  cmd->add_option(
      "scene_file", o.scene_file,
      "Scene file (JSON, see docs/scene-format.md), or - for standard input; its settings are "
      "overridden by the options");
  CLI::Option* scene_option =
      cmd->add_option("--scene", o.scene, "Built-in scene to render (see --list-scenes)")
          ->capture_default_str();
  cmd->add_flag("--list-scenes", o.list_scenes, "List the built-in scenes and exit");
  cmd->add_option("--like", o.like,
                  "Render again as this image's metadata records it (scene, size, samples, "
                  "seed, camera, ...); each option given replaces its part of that. Refused "
                  "where the scene is no longer the one the image was rendered from")
      ->type_name("IMAGE");
  cmd->add_option("--scene-seed", o.scene_seed, "Seed of the random layout of cover and spheres:N")
      ->check(kNotNegative)
      ->capture_default_str();
  return scene_option;
}

CLI::Option* add_image_options(CLI::App* cmd, RenderOptions& o) {
  CLI::Option* output_option =
      cmd->add_option("-o,--output", o.output,
                      "Output image; the format follows the extension (" + image_extensions() +
                          "). Default: <scene>.png in the working directory");
  // The ranges in the help come from the one table (core/limits/input_limits.h).
  const std::string side = std::to_string(limits::kMaxImageSide);
  cmd->add_option("--width", o.width,
                  "Image width in pixels, 1 to " + side + " (default: the scene's)");
  cmd->add_option("--height", o.height,
                  "Image height in pixels, 1 to " + side +
                      " (default: from the width and the scene's "
                      "aspect ratio)");
  cmd->add_option("--crop", o.crop,
                  "Render only the region X0,Y0,X1,Y1 of the image (pixels from its top left, "
                  "X1 and Y1 excluded): each pixel is the whole image's, bit for bit; an EXR "
                  "keeps the region's place in the frame (uniform sampling only)")
      ->expected(4)
      ->delimiter(',')
      ->type_name("X0,Y0,X1,Y1")
      ->transform(kDecimal);  // a whole-number option with a type name of its own
  cmd->add_option("--passes", o.passes,
                  "Add the first hit's passes to an .exr output, any of albedo, normal and depth "
                  "(channels albedo.R/G/B, N.X/Y/Z, Z), each the mean over the pixel's samples; "
                  "0 where a sample saw the sky, also Z (Cycles writes 1e10 there: a compositor "
                  "reads Z 0 as at the lens)")
      ->type_name("LIST");
  return output_option;
}

// Adaptive sampling: an error target per pixel or for the image, or a budget.
void add_adaptive_options(CLI::App* cmd, RenderOptions& o) {
  cmd->add_option("--target-error", o.target_error,
                  "Adaptive sampling: each pixel stops once its relative standard error is below "
                  "this (e.g. 0.05); --spp is then the most a pixel takes (default " +
                      std::to_string(kDefaultErrorDrivenMaxSpp) + ")")
      ->check(kFinitePositive);
  cmd->add_option("--image-error", o.image_error,
                  "Adaptive sampling: stop once the image's estimated relative RMS error is "
                  "below this (e.g. 0.02; it aims at 0.92 of it), giving each pixel samples in "
                  "proportion to "
                  "sqrt(variance / cost); --spp is then the most a pixel takes (default " +
                      std::to_string(kDefaultErrorDrivenMaxSpp) + ")")
      ->check(kFinitePositive);
  cmd->add_flag("--adaptive", o.adaptive,
                "Adaptive sampling on a budget: the time of --spp uniform samples (or "
                "--time-limit), spread over the pixels in proportion to sqrt(variance / cost), "
                "which gives the lowest image error for the time");
  cmd->add_option("--min-spp", o.min_spp,
                  "Adaptive sampling: samples every pixel takes before it may stop, at least 2 "
                  "(default " +
                      std::to_string(kDefaultLeastSamples) + ")");
}

// --threads as render, merge and denoise take it (the library refuses a count out of range).
void add_threads_option(CLI::App* cmd, int& threads) {
  cmd->add_option("--threads", threads,
                  "Worker threads, 0 (all cores) to " + std::to_string(limits::kMaxThreads))
      ->capture_default_str();
}

void add_sampling_options(CLI::App* cmd, RenderOptions& o) {
  cmd->add_option("--spp", o.spp, "Samples per pixel (default: the scene's)");
  cmd->add_option("--depth", o.depth,
                  "Maximum rays per path, 0 to " + std::to_string(limits::kMaxDepth) +
                      " (default: the scene's)");
  cmd->add_option("--seed", o.seed, "Seed of the sample streams, 0 to 2^64-1")
      ->check(kNotNegative)
      ->capture_default_str();
  add_threads_option(cmd, o.threads);
  cmd->add_option("--accel", o.accel, "Intersector: embree or naive (same image, other speed)")
      ->capture_default_str();
  cmd->add_option("--time-limit", o.time_limit,
                  "Render in passes until this many seconds are spent (ends within one pass; "
                  "0: no limit); the file holds the samples completed. With --spp, stop at "
                  "that many")
      ->check(kFiniteNotNegative);
  cmd->add_option("--sampler", o.sampler,
                  "Sampler: sobol (one Owen-scrambled Sobol point for pixel, lens and the first "
                  "three bounces, padded Sobol for later bounces: 2.3-5.4x lower relMSE at "
                  "equal time on the built-in scenes), independent (the book's) or padded-sobol "
                  "(every 1D and 2D dimension its own scrambled Sobol sequence)")
      ->check(CLI::IsMember(sampler_name_list()))
      ->capture_default_str();
  cmd->add_option("--roulette", o.roulette,
                  "Russian roulette: on (from the third ray, a path carrying less than 0.2 in "
                  "every channel goes on with that share of chance, weighted up; 7% less time on "
                  "the cover, same expected image) or off (every path to --depth, the book's "
                  "estimator: for comparisons with the book's program ray for ray)")
      ->check(CLI::IsMember({roulette_name(true), roulette_name(false)}))
      ->capture_default_str();
  add_adaptive_options(cmd, o);
  cmd->add_flag("--denoise", o.denoise,
                "Write the denoised image (a feature regression on the first hits' albedo, "
                "normal and depth; its estimated error on the summary line); an .exr also keeps "
                "the noisy image (noisy.R/G/B) and each pixel's estimated squared error "
                "(denoise.mse.R/G/B). With --image-error, renders until the denoised image's "
                "estimated error is below it, every pixel the same count. With --part, the part "
                "keeps what 'rtiow denoise' needs");
  cmd->add_flag("--stats-channels", o.stats_channels,
                "Add per-pixel channels to an .exr output: spp and the variance of the pixel's "
                "mean (variance.R/G/B). For that estimate the samples alternate between two "
                "independent replicates, whose image has about 1.2x the squared error of one "
                "sequence at a fixed count; with --part, so that 'rtiow merge --stats-channels' "
                "can write them");
  cmd->add_option("--fresnel", o.fresnel,
                  "Glass reflectance: schlick (the book's approximation) or exact (default: as "
                  "the scene says, schlick for the built-in scenes)")
      ->check(CLI::IsMember({std::string(to_string(FresnelModel::Schlick)),
                             std::string(to_string(FresnelModel::Exact))}));
}

void add_run_options(CLI::App* cmd, RenderOptions& o) {
  cmd->add_flag("-q,--quiet", o.quiet, "No progress or summary on stderr");
  cmd->add_option("--summary-json", o.summary_json,
                  "Also write the render's summary as JSON here, for scripts: time, rays, rate, "
                  "samples, threads, the error asked and reached, the exit code (schema in "
                  "docs/usage.md); written after the image, also when a signal stops the render");
  cmd->add_option("--preview", o.preview_seconds,
                  "Watch the render: every this many seconds, replace the output with the "
                  "samples so far (its metadata says how far), for any viewer that reloads; the "
                  "finished file is the same, byte for byte (0: no preview)")
      ->check(kFiniteNotNegative);
  cmd->add_option("--display", o.display,
                  "Watch the render in the tev viewer at HOST:PORT (tev's default: "
                  "127.0.0.1:14158), sent at each --preview (every second without it) and at the "
                  "end; an unreachable viewer is a warning, not an error")
      ->type_name("HOST:PORT");
  cmd->add_option(
      "--sample-range", o.sample_range,
      "Render only samples A:B (from sample A up to, not including, B; B at most --spp, "
      "the job's total) of every pixel "
      "into a part file (.exr) for 'rtiow merge' (render farms)");
  cmd->add_option("--part", o.part,
                  "Render the i-th of n equal shares of the samples (i/n, from 0) into a part "
                  "file (.exr)");
  cmd->add_option("--checkpoint", o.checkpoint_seconds,
                  "Keep the render's state in <output>.rtiow-checkpoint, saved every this many "
                  "seconds and when a signal stops it, and removed when the render finishes "
                  "(0: no checkpoint)")
      ->check(kFiniteNotNegative)
      ->capture_default_str();
  cmd->add_flag("--resume", o.resume,
                "Continue the render of the same request from its checkpoint (to more samples "
                "with a larger --spp); without a checkpoint, render from the start");
  cmd->add_flag("--restart", o.restart,
                "Discard the checkpoint beside the output and render from the start (a render "
                "never replaces a checkpoint unless told: --resume or --restart)");
  cmd->add_flag("--keep-state", o.keep_state,
                "Keep the checkpoint of a finished render (compact, about 60 bytes a pixel), so "
                "--resume with a larger --spp refines it; without it, a finished render removes "
                "its checkpoint");
  cmd->add_flag("--reproducible", o.reproducible,
                "Leave wall-clock metadata (render time) out of the file, so the same scene, "
                "settings and seed give a byte-identical file");
}

void add_camera_options(CLI::App* cmd, RenderOptions& o) {
  cmd->add_option("--lookfrom", o.lookfrom, "Camera position x,y,z (overrides the scene)")
      ->expected(3)
      ->delimiter(',')
      ->type_name("X,Y,Z");
  cmd->add_option("--lookat", o.lookat, "Point the camera looks at x,y,z")
      ->expected(3)
      ->delimiter(',')
      ->type_name("X,Y,Z");
  cmd->add_option("--vup", o.vup, "Camera up vector x,y,z")
      ->expected(3)
      ->delimiter(',')
      ->type_name("X,Y,Z");
  cmd->add_option("--vfov", o.vfov, "Vertical field of view in degrees, in (0, 180)");
  cmd->add_option("--aperture", o.aperture, "Lens diameter (0: pinhole)");
  cmd->add_option("--focus-dist", o.focus_distance, "Distance to the plane in focus");
}

// --help lists the options in groups, in this order: 40 options in one list were a wall.
void group_options(CLI::App* cmd) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> groups = {
      {"Scene", {"--scene", "--list-scenes", "--like", "--scene-seed"}},
      {"Output",
       {"-o", "--width", "--height", "--crop", "--passes", "--denoise", "--stats-channels",
        "--reproducible", "-q", "--summary-json", "--preview", "--display"}},
      {"Sampling",
       {"--spp", "--depth", "--seed", "--sampler", "--roulette", "--fresnel", "--adaptive",
        "--image-error", "--target-error", "--min-spp"}},
      {"Camera (each replaces the scene's)",
       {"--lookfrom", "--lookat", "--vup", "--vfov", "--aperture", "--focus-dist"}},
      {"Long renders", {"--time-limit", "--checkpoint", "--resume", "--restart", "--keep-state"}},
      {"Speed and distribution", {"--threads", "--accel", "--part", "--sample-range"}},
  };
  for (const auto& [group, names] : groups) {
    for (const std::string& name : names) cmd->get_option(name)->group(group);
  }
}

CLI::App* add_render(CLI::App& app, RenderCommand& c) {
  RenderOptions& o = c.options;
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Render a scene file or a built-in scene to an image (with no options: the book's cover "
      "at its final settings, to cover.png)");
  add_scene_options(cmd, o);
  add_image_options(cmd, o);
  add_sampling_options(cmd, o);
  add_run_options(cmd, o);
  add_camera_options(cmd, o);
  group_options(cmd);
  return cmd;
}

// What the user typed of the render's options, once parsed.
void note_typed_render_options(CLI::App* cmd, RenderCommand& c) {
  const auto typed = [cmd](const std::string& name) { return cmd->get_option(name)->count() > 0; };
  c.scene_named = typed("--scene");
  c.output_given = typed("--output");
  // The library's names of the settings, as this command line spells them.
  c.typed = parts_given([&](std::string_view setting) {
    if (setting == "scene_file") return typed("scene_file");  // the positional argument
    if (setting == "focus_distance") return typed("--focus-dist");
    std::string option = "--";
    for (const char ch : setting) option.push_back(ch == '_' ? '-' : ch);
    return typed(option);
  });
  const ImageFormat* format = c.output_given ? image_format(c.options.output) : nullptr;
  c.output_holds_channels = format && format->extra_channels;
}

// ---- rtiow scene, merge, diff

CLI::App* add_scene(CLI::App& app, SceneOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "scene", "Write a built-in scene as a scene file (JSON) that renders the same image");
  cmd->add_option("name", o.name, "Built-in scene (see rtiow render --list-scenes)")->required();
  cmd->add_option("--scene-seed", o.scene_seed, "Seed of the random layout of cover and spheres:N")
      ->check(kNotNegative)
      ->capture_default_str();
  cmd->add_option("-o,--output", o.output, "Write here instead of to stdout ('-')");
  return cmd;
}

// merge's and denoise's --summary-json (core/session/merge_summary.h).
void add_merge_summary_option(CLI::App* cmd, MergeOptions& o) {
  cmd->add_option("--summary-json", o.summary_json,
                  "Also write the merge's summary as JSON here, for scripts: the parts, the "
                  "image's size, samples and estimated error, the denoiser's figures, threads, "
                  "time (schema in docs/usage.md); written after the image");
}

CLI::App* add_merge(CLI::App& app, MergeOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "merge",
      "Add part files (rtiow render --sample-range/--part) into the image one render "
      "would have produced; checks they belong together, overlap nowhere and miss nothing");
  cmd->add_option("parts", o.parts, "Part files (.exr)")->required();
  cmd->add_option("-o,--output", o.output,
                  "The merged image (" + image_extensions() + "); not one of the parts")
      ->required();
  cmd->add_flag("--stats-channels", o.stats_channels,
                "Add per-pixel channels to an .exr output: spp and the variance of the pixel's "
                "mean (variance.R/G/B), the same as one render's --stats-channels");
  cmd->add_flag("--denoise", o.denoise,
                "Write the merged render denoised, as 'rtiow denoise' does (the parts rendered "
                "with --denoise)");
  add_threads_option(cmd, o.threads);
  add_merge_summary_option(cmd, o);
  cmd->add_flag("-q,--quiet", o.quiet, "No progress or summary on stderr");
  return cmd;
}

CLI::App* add_denoise(CLI::App& app, MergeOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "denoise",
      "Denoise a render kept as part files (rtiow render --denoise --part i/n, or --part 0/1 "
      "for a whole render): merges them and writes the denoised image with its estimated error");
  cmd->add_option("parts", o.parts, "Part files (.exr) rendered with --denoise")->required();
  cmd->add_option("-o,--output", o.output,
                  "The denoised image (" + image_extensions() + "); not one of the parts")
      ->required();
  cmd->add_flag("--stats-channels", o.stats_channels,
                "Add the spp and variance channels to an .exr output, as merge does");
  add_threads_option(cmd, o.threads);
  add_merge_summary_option(cmd, o);
  cmd->add_flag("-q,--quiet", o.quiet, "No progress or summary on stderr");
  return cmd;
}

// A plain comparison's thresholds.
void add_plain_options(CLI::App* cmd, PlainThresholds& t) {
  cmd->add_option("--fail", t.fail, "Plain: a pixel fails when a channel differs by more")
      ->check(kFiniteNotNegative)
      ->capture_default_str();
  cmd->add_option("--failpercent", t.fail_percent,
                  "Plain: the percentage of failing pixels allowed")
      ->check(kFiniteNotNegative)
      ->capture_default_str();
  cmd->add_option("--hardfail", t.hard_fail,
                  "Plain: fail when any channel differs by more (default: no limit)")
      ->check(kFiniteNotNegative);
  cmd->add_option("--warn", t.warn,
                  "Plain: a pixel warns when a channel differs by more (default: --fail's value "
                  "when --fail is given)")
      ->check(kFiniteNotNegative)
      ->capture_default_str();
  cmd->add_option("--warnpercent", t.warn_percent,
                  "Plain: the percentage of warning pixels allowed (default: --failpercent's "
                  "value when --failpercent is given)")
      ->check(kFiniteNotNegative)
      ->capture_default_str();
}

// A noise-aware comparison's test.
void add_noise_options(CLI::App* cmd, ComparisonSettings& s) {
  cmd->add_option("--alpha", s.alpha,
                  "Noise-aware: the chance that noise alone fails the comparison (half for the "
                  "image mean, half over the blocks), 1e-12 to 0.5")
      ->check(kFiniteNotNegative)
      ->check(from_to(1e-12, 0.5))
      ->capture_default_str();
  cmd->add_option("--block", s.block, "Noise-aware: the side of a block of pixels, 1 to 4096")
      ->check(from_to(1, 4096))
      ->capture_default_str();
}

CLI::App* add_diff(CLI::App& app, DiffOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "diff",
      "Compare a test image, or several renders with other seeds, with a reference. Exit 0 "
      "pass, 1 warning, 2 failure; no verdict: 3 images of other sizes (or linear against "
      "8-bit), 4 a missing or unreadable file or a bad option. Noise-aware when given several "
      "renders or when both images carry variance channels (--stats-channels EXR): then a "
      "difference fails only where the noise cannot explain it");
  cmd->add_option("reference", o.reference, "The reference image")->required();
  cmd->add_option("test", o.tests,
                  "The image to check, or several renders of the same job with other seeds")
      ->required();
  cmd->add_option("--mode", o.settings.mode,
                  "auto (seeds for several tests; noise when both images have variances; else "
                  "plain), plain, noise, or seeds")
      ->check(CLI::IsMember({"auto", "plain", "noise", "seeds"}))
      ->capture_default_str();
  add_plain_options(cmd, o.settings.thresholds);
  add_noise_options(cmd, o.settings);
  cmd->add_option("--out-diff", o.out_diff,
                  "Write |test - reference| (several tests: their mean), scaled so the largest "
                  "difference is white");
  cmd->add_option("--summary-json", o.summary_json,
                  "Also write the verdict and the figures as JSON here, for scripts (schema in "
                  "docs/diff.md)");
  cmd->add_option("--out-z", o.out_z,
                  "Noise-aware: write the blocks' z (or t) scores (red: test brighter, blue: "
                  "darker, full colour at the critical value)");
  return cmd;
}

// A warning threshold left unset follows the failure one given, so plain thresholds for
// failure alone do not leave every image warning at 1e-6.
void follow_failure_thresholds(CLI::App* cmd, PlainThresholds& t) {
  if (cmd->count("--fail") > 0 && cmd->count("--warn") == 0) t.warn = t.fail;
  if (cmd->count("--failpercent") > 0 && cmd->count("--warnpercent") == 0) {
    t.warn_percent = t.fail_percent;
  }
}

// ---- rtiow bench, bench-point, accuracy

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

// What is swept: the scene, its size, the sample counts and the settings compared.
void add_accuracy_sweep_options(CLI::App* cmd, AccuracyOptions& o) {
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
void add_accuracy_run_options(CLI::App* cmd, AccuracyOptions& o) {
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

CLI::App* add_accuracy(CLI::App& app, AccuracyOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "accuracy",
      "Measure speed against accuracy on a scene: error against a cached high-spp reference "
      "for spp 1..N with each sampler, adaptive sampling (budget, image error, target error), "
      "the time to the book's quality (against the book's estimator: independent sampling "
      "without Russian roulette), the depth limit, the intersector and the Fresnel "
      "model; prints tables, writes JSON, CSV and a PNG plot (about 2 minutes on a 2-core "
      "machine, the reference cached after the first run; --quick: a few seconds)");
  add_accuracy_sweep_options(cmd, o);
  add_accuracy_run_options(cmd, o);
  return cmd;
}

void apply_quick_runs(CLI::App* bench, const BenchOptions& b, CLI::App* accuracy,
                      const AccuracyOptions& a) {
  if (bench->parsed() && b.quick && b.compare.empty()) {
    apply_quick_run(*bench, {{"--width", "200"},
                             {"--height", "112"},
                             {"--spp", "4"},
                             {"--scaling-width", "200"},
                             {"--scaling-height", "112"},
                             {"--max-spheres", "10000"},
                             {"--naive-budget", "5"},
                             {"--repeat", "1"}});
  }
  if (accuracy->parsed() && a.quick) {
    apply_quick_run(*accuracy, {{"--width", "80"},
                                {"--reference-spp", "1024"},
                                {"--max-spp", "256"},
                                {"--fixed-spp", "16"},
                                {"--book-spp", "64"},
                                {"--depths", "1,2,4,8,50"},
                                {"--target-errors", "0.2,0.1"},
                                {"--image-errors", "0.1,0.05"},
                                {"--repeat", "1"}});
  }
}

// ---- the whole command line

// Help and version text; a failed write (a full disk, a closed pipe) is an error too.
int print_and_exit(const CLI::App& app, const CLI::Error& e) {
  const int code = app.exit(e);
  std::cout.flush();
  if (!std::cout || std::fflush(stdout) != 0) {
    report_error("cannot write to standard output");
    return 1;
  }
  return code;
}

// A first word that is no command, or no option rtiow itself takes: name it, with the nearest
// real one (CLI11 would only say that a command is required). Returns true if it refused;
// says so if `speaks` (under mpirun, rank 0 speaks for all).
bool refused_unknown_command(const CLI::App& app, int argc, char** argv, bool speaks) {
  if (argc < 2) return false;
  const std::string first = argv[1];
  std::vector<std::string> names;
  if (first[0] == '-') {
    names = option_spellings(app);
    if (std::find(names.begin(), names.end(), first.substr(0, first.find('='))) != names.end())
      return false;
  } else {
    for (const CLI::App* sub : app.get_subcommands({})) {
      if (sub->get_name() == first) return false;
      if (!sub->get_group().empty()) names.push_back(sub->get_name());  // not the hidden ones
    }
  }
  std::string known;
  for (const std::string& name : names) known += (known.empty() ? "" : ", ") + name;
  const std::string what = first[0] == '-' ? "unknown option " : "unknown command ";
  if (!speaks) return true;
  report_error(what + quote_value(first) + did_you_mean(first, names) + " (known: " + known +
               "; see rtiow --help)");
  return true;
}

// The commands, each bound to its part of `out`, in the order --help lists them.
struct Commands {
  CLI::App *render, *scene, *merge, *denoise, *bench, *point, *accuracy, *diff;
};

Commands add_commands(CLI::App& app, CommandLine& out) {
  Commands c{};
  c.render = add_render(app, out.render);
  c.scene = add_scene(app, out.scene);
  c.merge = add_merge(app, out.merge);
  c.denoise = add_denoise(app, out.denoise);
  c.bench = add_bench_options(app, out.bench);
  c.point = add_point_options(app, out.point);
  c.accuracy = add_accuracy(app, out.accuracy);
  c.diff = add_diff(app, out.diff);
  return c;
}

// Which command was parsed, with what its options mean beyond their values.
void finish_parsed(const Commands& c, CommandLine& out) {
  apply_quick_runs(c.bench, out.bench, c.accuracy, out.accuracy);
  const std::pair<CLI::App*, Command> commands[] = {
      {c.render, Command::Render},     {c.scene, Command::Scene}, {c.merge, Command::Merge},
      {c.denoise, Command::Denoise},   {c.bench, Command::Bench}, {c.point, Command::BenchPoint},
      {c.accuracy, Command::Accuracy}, {c.diff, Command::Diff}};
  for (const auto& [cmd, command] : commands) {
    if (cmd->parsed()) out.command = command;
  }
  if (c.render->parsed()) note_typed_render_options(c.render, out.render);
  out.denoise.denoise = true, out.denoise.command = "denoise";
  out.scene.output_given = c.scene->get_option("--output")->count() > 0;
  follow_failure_thresholds(c.diff, out.diff.settings.thresholds);
}

}  // namespace

std::optional<int> parse_command_line(int argc, char** argv, const std::string& version_text,
                                      bool speaks, CommandLine& out) {
  CLI::App app{
      "rtiow: a path tracer for the scenes of Ray Tracing in One Weekend, "
      "built on Embree, oneTBB and OpenImageIO",
      "rtiow"};
  // Before the commands are added: each takes its parent's formatter.
  app.formatter(readable_help_formatter());
  app.require_subcommand(1);
  app.set_version_flag("--version", version_text);
  app.footer(
      "The docs/ pages the help cites are in the source tree, and in share/doc/rtiow/ where "
      "rtiow is installed.");
  const Commands commands = add_commands(app, out);
  read_whole_numbers_as_decimal(app);
  // Under mpirun every rank parses the same command line: rank 0 alone prints what it says.
  if (refused_unknown_command(app, argc, argv, speaks)) return 2;
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return speaks ? print_and_exit(app, e) : 0;
  } catch (const CLI::CallForAllHelp& e) {
    return speaks ? print_and_exit(app, e) : 0;
  } catch (const CLI::CallForVersion& e) {
    return speaks ? print_and_exit(app, e) : 0;
  } catch (const CLI::ParseError& e) {
    if (speaks) report_error(explain_parse_error(app, e));
    // diff's 2 is a verdict (FAILURE): a command line it cannot use is "could not compare".
    return argc > 1 && std::string_view(argv[1]) == "diff" ? kDiffCouldNotCompare : 2;
  }
  finish_parsed(commands, out);
  return std::nullopt;
}

}  // namespace rtiow
