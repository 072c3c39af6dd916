#include "app/render_command.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/cli_checks.h"
#include "app/interrupt.h"
#include "app/mpi_session.h"
#include "app/progress_display.h"
#include "core/film/render_statistics.h"
#include "core/io/error.h"
#include "core/io/image_output.h"
#include "core/io/input_limits.h"
#include "core/io/output_path.h"
#include "core/render/render.h"
#include "core/render/render_loop.h"
#include "core/render/render_part.h"
#include "core/scene/builtin_scenes.h"
#include "core/scene/scene_file.h"

namespace rtiow {
namespace {

struct RenderOptions {
  std::string scene_file;
  std::string scene = "cover";
  std::uint64_t scene_seed = 1;
  bool list_scenes = false;
  std::string output;
  std::optional<int> width, height, spp, depth;
  std::uint64_t seed = 1;
  int threads = 0;
  std::string accel = "embree";
  std::string fresnel;  // empty: as the scene says
  double time_limit = 0.0;
  std::string sampler = "independent";
  double target_error = 0.0;
  int min_spp = 16;
  bool stats_channels = false;
  bool quiet = false;
  bool reproducible = false;
  std::string sample_range;  // "A:B": render a share of the samples into a part file
  std::string part;          // "i/n": the i-th of n equal shares
  std::vector<double> lookfrom, lookat, vup;
  std::optional<double> vfov, aperture, focus_distance;
};

constexpr int kDefaultAdaptiveMaxSpp = 8192;

Vec3d to_vec3(const std::vector<double>& v) {
  return {v[0], v[1], v[2]};
}

// The side an image takes from the other and the aspect ratio: checked, never clamped.
int derived_side(int given, double ratio, const char* side, const char* option) {
  if (given < 1 || given > limits::kMaxImageSide) return given;  // validate() names it
  const double derived = std::round(double(given) * ratio);
  if (!(derived >= 1.0 && derived <= double(limits::kMaxImageSide))) {
    char text[64];
    std::snprintf(text, sizeof text, "%.6g", derived);
    throw InvalidInput(std::string("the scene's aspect ratio gives a ") + side + " of " + text +
                       " pixels for " + option + " " + std::to_string(given) + " (must be 1 to " +
                       std::to_string(limits::kMaxImageSide) + "): give both sides");
  }
  return int(derived);
}

// The scene's own camera and image settings, overridden by whatever the user gave.
void apply_overrides(const RenderOptions& o, Scene& scene, RenderSettings& settings) {
  CameraSettings& cam = scene.camera;
  if (!o.lookfrom.empty()) cam.lookfrom = to_vec3(o.lookfrom);
  if (!o.lookat.empty()) cam.lookat = to_vec3(o.lookat);
  if (!o.vup.empty()) cam.vup = to_vec3(o.vup);
  if (o.vfov) cam.vfov_degrees = *o.vfov;
  if (o.aperture) cam.aperture = *o.aperture;
  if (o.focus_distance) cam.focus_distance = *o.focus_distance;
  if (!o.fresnel.empty()) {
    const FresnelModel model = o.fresnel == "exact" ? FresnelModel::Exact : FresnelModel::Schlick;
    for (Material& m : scene.materials) {
      if (auto* d = std::get_if<Dielectric>(&m)) d->fresnel = model;
    }
  }

  const ImageSettings& image = scene.image;
  if (o.width && o.height) {
    settings.width = *o.width, settings.height = *o.height;
  } else if (o.height) {
    settings.height = *o.height;
    settings.width = derived_side(*o.height, image.aspect_ratio, "width", "--height");
  } else {
    settings.width = o.width.value_or(image.width);
    settings.height = derived_side(settings.width, 1.0 / image.aspect_ratio, "height", "--width");
  }
  // With a target error and no --spp, a pixel takes at most kDefaultAdaptiveMaxSpp; with
  // only a time limit, samples are added until the time is spent.
  settings.samples_per_pixel = o.spp.value_or(o.target_error > 0 ? kDefaultAdaptiveMaxSpp
                                              : o.time_limit > 0 ? std::numeric_limits<int>::max()
                                                                 : image.samples_per_pixel);
  settings.time_limit_seconds = o.time_limit;
  settings.sampler = parse_sampler(o.sampler);
  settings.target_error = o.target_error;
  settings.min_samples = o.min_spp;
  settings.max_depth = o.depth.value_or(image.max_depth);
  settings.seed = o.seed;
  settings.threads = o.threads;
}

// The default output: the scene's name made a safe file name, in the working directory.
std::string default_output(const std::string& scene) {
  return safe_file_stem(scene) + ".png";
}

int list_scenes() {
  for (const auto& s : builtin_scenes())
    std::printf("%-16s %s\n", s.name.c_str(), s.summary.c_str());
  return 0;
}

// "64 spp", or for adaptive sampling the range and mean of the pixels' counts.
std::string describe_samples(const RenderSettings& s, const RenderResult& r) {
  char text[96];
  if (s.target_error > 0) {
    const auto [least, most] = std::minmax_element(r.pixel_samples.begin(), r.pixel_samples.end());
    std::snprintf(text, sizeof text, "%u-%u spp (mean %.1f, target error %g)", *least, *most,
                  mean_samples(r), s.target_error);
  } else {
    std::snprintf(text, sizeof text, "%d spp", r.samples_completed);
  }
  return text;
}

Metadata make_metadata(const RenderOptions& o, const Scene& scene, const RenderSettings& s,
                       const RenderResult& r) {
  Metadata metadata{{"scene", scene.name}};
  if (scene.layout_seed) metadata.emplace_back("scene_seed", std::int64_t(*scene.layout_seed));
  metadata.insert(metadata.end(), {
                                      {"depth", std::int64_t(s.max_depth)},
                                      {"seed", std::int64_t(s.seed)},
                                      {"sampler", to_string(s.sampler)},
                                      {"accelerator", to_string(s.accel)},
                                      {"rays_traced", std::int64_t(r.rays_traced)},
                                  });
  if (s.target_error > 0) {
    // Each pixel has its own count: the range and the mean, not one "spp".
    const auto [least, most] = std::minmax_element(r.pixel_samples.begin(), r.pixel_samples.end());
    metadata.insert(metadata.end(), {
                                        {"target_error", s.target_error},
                                        {"spp_min", std::int64_t(*least)},
                                        {"spp_max", std::int64_t(*most)},
                                        {"spp_mean", mean_samples(r)},
                                        {"spp_limit", std::int64_t(s.samples_per_pixel)},
                                    });
  } else {
    metadata.emplace_back("spp", std::int64_t(r.samples_completed));
  }
  if (r.stopped) {
    if (s.target_error <= 0)
      metadata.emplace_back("spp_requested", std::int64_t(s.samples_per_pixel));
    metadata.emplace_back("stopped", std::string("interrupted by a signal"));
  } else if (r.time_limited) {
    char limit[64];
    std::snprintf(limit, sizeof limit, "time limit of %g s", s.time_limit_seconds);
    metadata.emplace_back("stopped", std::string(limit));
  }
  if (!o.reproducible) metadata.emplace_back("render_seconds", r.render_seconds);
  return metadata;
}

Scene load_scene(const RenderOptions& o, bool scene_option_given) {
  if (o.scene_file.empty()) return make_builtin_scene(o.scene, o.scene_seed);
  if (scene_option_given) {
    throw InvalidInput("give a scene file or --scene, not both");
  }
  return load_scene_file(o.scene_file);
}

// The output: as given (an empty -o is an error, not the default), or named after the scene.
std::string output_path(const RenderOptions& o, bool output_given, const Scene& scene) {
  if (output_given && o.output.empty()) throw InvalidInput("-o/--output: the path is empty");
  return output_given ? o.output : default_output(scene.name);
}

// "A<sep>B" as two whole numbers, or nothing (no sign, no spaces, no overflow).
std::optional<std::pair<std::uint64_t, std::uint64_t>> parse_pair(const std::string& text,
                                                                  char separator) {
  const auto at = text.find(separator);
  if (at == std::string::npos) return std::nullopt;
  std::uint64_t a = 0, b = 0;
  const char* end = text.data() + text.size();
  const auto first = std::from_chars(text.data(), text.data() + at, a);
  const auto second = std::from_chars(text.data() + at + 1, end, b);
  if (at == 0 || first.ec != std::errc() || first.ptr != text.data() + at ||
      second.ec != std::errc() || second.ptr != end || at + 1 == text.size()) {
    return std::nullopt;
  }
  return std::pair{a, b};
}

// "A:B" or "i/n" into the share of samples this process renders; nothing when neither.
// The job is settings.samples_per_pixel samples; a share must lie within it.
void apply_share(const RenderOptions& o, const std::string& output, RenderSettings& settings) {
  if (o.sample_range.empty() && o.part.empty()) return;
  if (!o.sample_range.empty() && !o.part.empty()) {
    throw InvalidInput("give --sample-range or --part, not both");
  }
  if (image_format(output) == nullptr || !image_format(output)->extra_channels) {
    throw InvalidInput("output " + quote_value(output) +
                       ": a share of a render is written as a part file, which must be .exr");
  }
  const auto total = std::uint64_t(settings.samples_per_pixel);
  if (!o.part.empty()) {
    const auto share = parse_pair(o.part, '/');
    if (!share) throw InvalidInput("--part " + quote_value(o.part) + ": expected i/n, e.g. 0/4");
    const auto [i, n] = *share;
    if (n == 0 || i >= n) throw InvalidInput("--part " + quote_value(o.part) + ": need 0 <= i < n");
    if (n > total) {
      throw InvalidInput("--part " + quote_value(o.part) + ": " + std::to_string(total) +
                         " samples per pixel do not make " + std::to_string(n) + " shares");
    }
    settings.first_sample = total * i / n;  // n <= total < 2^31: no overflow
    settings.samples_per_pixel = int(total * (i + 1) / n - settings.first_sample);
    return;
  }
  const auto range = parse_pair(o.sample_range, ':');
  if (!range) {
    throw InvalidInput("--sample-range " + quote_value(o.sample_range) +
                       ": expected A:B, e.g. 0:100");
  }
  const auto [a, b] = *range;
  if (a >= b || b > total) {
    throw InvalidInput("--sample-range " + quote_value(o.sample_range) +
                       ": need A < B <= the job's " + std::to_string(total) +
                       " samples per pixel (--spp)");
  }
  settings.first_sample = a;
  settings.samples_per_pixel = int(b - a);
}

// Under mpirun: this rank's equal share of the samples of every pixel.
void apply_rank_share(const RenderOptions& o, const MpiSession& mpi, RenderSettings& settings) {
  if (!mpi.distributed()) return;
  if (!o.sample_range.empty() || !o.part.empty()) {
    throw InvalidInput(
        "--sample-range and --part are for separate jobs; under mpirun the ranks "
        "share the samples themselves");
  }
  const auto total = std::uint64_t(settings.samples_per_pixel);
  const auto ranks = std::uint64_t(mpi.size()), rank = std::uint64_t(mpi.rank());
  if (total < ranks) {
    throw InvalidInput(std::to_string(total) + " samples per pixel cannot be shared by " +
                       std::to_string(ranks) + " ranks");
  }
  settings.first_sample = total * rank / ranks;
  settings.samples_per_pixel = int(total * (rank + 1) / ranks - settings.first_sample);
}

// Adaptive sampling decides each pixel's stop on all its samples, so it cannot be split
// into shares; the statistics channels need a format with room for them.
void check_adaptive_options(const RenderOptions& o, const std::string& output,
                            const MpiSession& mpi) {
  const ImageFormat* format = image_format(output);
  if (o.stats_channels && format && !format->extra_channels) {
    throw InvalidInput("--stats-channels: output " + quote_value(output) +
                       " must be .exr to hold the spp and variance channels");
  }
  if (o.target_error > 0 && (!o.sample_range.empty() || !o.part.empty() || mpi.distributed())) {
    throw InvalidInput(
        "--target-error needs all of a pixel's samples in one process: it cannot be combined "
        "with --sample-range, --part or mpirun");
  }
  if (o.stats_channels && (!o.sample_range.empty() || !o.part.empty() || mpi.distributed())) {
    throw InvalidInput("--stats-channels is for a render in one process, not a part or mpirun");
  }
}

int run_render(const RenderOptions& o, bool scene_option_given, bool output_given,
               const MpiSession& mpi) {
  if (o.list_scenes) return mpi.rank() == 0 ? list_scenes() : 0;

  // Cheap checks of the output first, so a bad -o is refused before a large scene loads.
  if (output_given) {
    check_output_path(
        output_path(o, output_given, Scene{}),
        o.scene_file.empty() ? std::vector<std::string>{} : std::vector<std::string>{o.scene_file});
  }
  Scene scene = load_scene(o, scene_option_given);
  RenderSettings settings;
  settings.accel = parse_accel(o.accel);
  apply_overrides(o, scene, settings);
  const int samples_asked = settings.samples_per_pixel;
  const std::string output = output_path(o, output_given, scene);
  const bool share = !o.sample_range.empty() || !o.part.empty();
  validate(settings);  // the whole job, before it is cut into a share
  apply_share(o, output, settings);
  apply_rank_share(o, mpi, settings);
  check_adaptive_options(o, output, mpi);
  check_image_output(
      output,
      o.scene_file.empty() ? std::vector<std::string>{} : std::vector<std::string>{o.scene_file},
      o.stats_channels);
  validate(scene, settings);

  RenderProgress progress;
  RenderResult result;
  {
    const InterruptGuard interrupt(progress.stop_requested);
    std::unique_ptr<ProgressDisplay> display;
    // Under MPI rank 0 shows its own share, which moves with the others' (equal shares).
    if (!o.quiet && mpi.rank() == 0) {
      // Adaptive sampling and an open-ended time limit have no total to show progress against.
      const bool open_ended = settings.target_error > 0 ||
                              settings.samples_per_pixel == std::numeric_limits<int>::max();
      display = std::make_unique<ProgressDisplay>(
          progress, open_ended ? 0
                               : std::uint64_t(settings.width) * std::uint64_t(settings.height) *
                                     std::uint64_t(settings.samples_per_pixel));
    }
    result = render(scene, settings, &progress);
  }
  if (mpi.distributed()) {
    // Rank 0 adds every rank's exact sums: the image of one process with all the samples.
    const std::uint64_t done = mpi.reduce_sum(std::uint64_t(result.samples_completed));
    result.rays_traced = mpi.reduce_sum(result.rays_traced);
    result.render_seconds = mpi.reduce_max(result.render_seconds);
    mpi.reduce_sums(result.sums);
    if (mpi.rank() != 0) return 0;
    result.stopped = done < std::uint64_t(samples_asked);
    result.samples_completed = int(done);
    resolve(result.sums, done, result.film);
    settings.samples_per_pixel = samples_asked;
    settings.first_sample = 0;
  }
  if (share) {
    RenderPart part;
    part.width = settings.width, part.height = settings.height;
    part.first_sample = settings.first_sample;
    part.samples = std::uint64_t(result.samples_completed);
    part.job_samples = std::uint64_t(samples_asked);
    part.digest = render_digest(scene, settings);
    part.metadata = make_metadata(o, scene, settings, result);
    part.sums = std::move(result.sums);
    write_part(output, part);
  } else {
    write_image(output, result.film, make_metadata(o, scene, settings, result),
                o.stats_channels ? statistics_channels(result) : std::vector<ExtraChannel>{});
  }
  if (result.stopped) {
    std::fprintf(stderr, "rtiow: interrupted: wrote %s (of %d asked) to %s\n",
                 describe_samples(settings, result).c_str(), settings.samples_per_pixel,
                 std::filesystem::absolute(output).c_str());
    return 128 + InterruptGuard::signal_received();
  }

  if (!o.quiet) {
    const double rays = double(result.rays_traced);
    const int threads =
        settings.threads > 0 ? settings.threads : int(std::thread::hardware_concurrency());
    const std::string ranks = mpi.distributed() ? std::to_string(mpi.size()) + " ranks x " : "";
    std::fprintf(stderr,
                 "rendered %s %dx%d, %s, depth %d, %s, %s%d thread%s: %.2f s, %.3g rays, "
                 "%.2f Mrays/s -> %s\n",
                 scene.name.c_str(), settings.width, settings.height,
                 describe_samples(settings, result).c_str(), settings.max_depth,
                 to_string(settings.accel).c_str(), ranks.c_str(), threads, threads == 1 ? "" : "s",
                 result.render_seconds, rays, rays / result.render_seconds * 1e-6,
                 std::filesystem::absolute(output).c_str());
  }
  return 0;
}

}  // namespace

std::function<int()> add_render_command(CLI::App& app, const MpiSession& mpi) {
  auto options = std::make_shared<RenderOptions>();
  RenderOptions& o = *options;
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Render a scene file or a built-in scene to an image (with no options: the book's cover "
      "at its final settings, to cover.png)");
  cmd->add_option("scene_file", o.scene_file,
                  "Scene file (JSON, see the README); its settings are overridden by the options");
  CLI::Option* scene_option =
      cmd->add_option("--scene", o.scene, "Built-in scene to render (see --list-scenes)")
          ->capture_default_str();
  cmd->add_flag("--list-scenes", o.list_scenes, "List the built-in scenes and exit");
  cmd->add_option("--scene-seed", o.scene_seed, "Seed of the random layout of cover and spheres:N")
      ->check(kNotNegative)
      ->capture_default_str();
  CLI::Option* output_option =
      cmd->add_option("-o,--output", o.output,
                      "Output image; the format follows the extension (" + image_extensions() +
                          "). Default: <scene>.png in the working directory");
  cmd->add_option("--width", o.width, "Image width in pixels, 1 to 2^20 (default: the scene's)");
  cmd->add_option("--height", o.height,
                  "Image height in pixels, 1 to 2^20 (default: from the width and the scene's "
                  "aspect ratio)");
  cmd->add_option("--spp", o.spp, "Samples per pixel (default: the scene's)");
  cmd->add_option("--depth", o.depth, "Maximum rays per path, 0 to 65536 (default: the scene's)");
  cmd->add_option("--seed", o.seed, "Seed of the sample streams, 0 to 2^64-1")
      ->check(kNotNegative)
      ->capture_default_str();
  cmd->add_option("--threads", o.threads, "Worker threads, 0 (all cores) to 1024")
      ->capture_default_str();
  cmd->add_option("--accel", o.accel, "Intersector: embree or naive (same image, other speed)")
      ->capture_default_str();
  cmd->add_option("--time-limit", o.time_limit,
                  "Render in passes until this many seconds are spent (ends within one pass); "
                  "the file holds the samples completed. With --spp, stop at that many")
      ->check(kFiniteNotNegative);
  cmd->add_option("--sampler", o.sampler,
                  "Sampler of the pixel position, lens and first bounce: independent (the book's) "
                  "or sobol (Owen-scrambled Sobol: on the cover 1.9x lower relMSE at 16 spp, 2.5x "
                  "at 64, 4x at 1024)")
      ->check(CLI::IsMember({"independent", "sobol"}))
      ->capture_default_str();
  cmd->add_option("--target-error", o.target_error,
                  "Adaptive sampling: each pixel stops once its relative standard error is below "
                  "this (e.g. 0.05); --spp is then the most a pixel takes (default 8192)")
      ->check(kFiniteNotNegative);
  cmd->add_option("--min-spp", o.min_spp,
                  "Adaptive sampling: samples every pixel takes before it may stop")
      ->check(CLI::Range(2, std::numeric_limits<int>::max()))
      ->capture_default_str();
  cmd->add_flag("--stats-channels", o.stats_channels,
                "Add per-pixel channels to an .exr output: spp and the variance of the pixel's "
                "mean (variance.R/G/B)");
  cmd->add_option("--fresnel", o.fresnel,
                  "Glass reflectance: schlick (the book's approximation) or exact (default: as "
                  "the scene says, schlick for the built-in scenes)")
      ->check(CLI::IsMember({"schlick", "exact"}));
  cmd->add_flag("-q,--quiet", o.quiet, "No progress or summary on stderr");
  cmd->add_option("--sample-range", o.sample_range,
                  "Render only samples A..B-1 (B at most --spp, the job's total) of every pixel "
                  "into a part file (.exr) for 'rtiow merge' (render farms)");
  cmd->add_option("--part", o.part,
                  "Render the i-th of n equal shares of the samples (i/n, from 0) into a part "
                  "file (.exr)");
  cmd->add_flag("--reproducible", o.reproducible,
                "Leave wall-clock metadata (render time) out of the file, so the same scene, "
                "settings and seed give a byte-identical file");
  cmd->add_option("--lookfrom", o.lookfrom, "Camera position x,y,z (overrides the scene)")
      ->expected(3)
      ->delimiter(',');
  cmd->add_option("--lookat", o.lookat, "Point the camera looks at x,y,z")
      ->expected(3)
      ->delimiter(',');
  cmd->add_option("--vup", o.vup, "Camera up vector x,y,z")->expected(3)->delimiter(',');
  cmd->add_option("--vfov", o.vfov, "Vertical field of view in degrees, in (0, 180)");
  cmd->add_option("--aperture", o.aperture, "Lens diameter (0: pinhole)");
  cmd->add_option("--focus-dist", o.focus_distance, "Distance to the plane in focus");
  return [options, cmd, scene_option, output_option, &mpi] {
    return cmd->parsed()
               ? run_render(*options, scene_option->count() > 0, output_option->count() > 0, mpi)
               : -1;
  };
}

}  // namespace rtiow
