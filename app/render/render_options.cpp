#include "app/render/render_options.h"

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "app/cli_checks.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/render/render_request.h"

namespace rtiow {
namespace {

Vec3d to_vec3(const std::vector<double>& v) {
  return {v[0], v[1], v[2]};
}

// The options as the core's request of a render.
RenderRequest request_of(const RenderOptions& o) {
  RenderRequest r;
  r.width = o.width, r.height = o.height;
  if (!o.crop.empty()) r.crop = PixelRegion{o.crop[0], o.crop[1], o.crop[2], o.crop[3]};
  r.spp = o.spp;
  r.max_depth = o.depth;
  CameraOverrides& cam = r.camera;
  if (!o.lookfrom.empty()) cam.lookfrom = to_vec3(o.lookfrom);
  if (!o.lookat.empty()) cam.lookat = to_vec3(o.lookat);
  if (!o.vup.empty()) cam.vup = to_vec3(o.vup);
  cam.vfov_degrees = o.vfov, cam.aperture = o.aperture, cam.focus_distance = o.focus_distance;
  if (!o.fresnel.empty()) r.fresnel = parse_fresnel(o.fresnel).value();  // CLI11 checked it
  r.sampler = parse_sampler(o.sampler);
  r.accel = parse_accel(o.accel);
  r.seed = o.seed;
  r.threads = o.threads;
  r.time_limit_seconds = o.time_limit;
  r.target_error = o.target_error;
  r.image_error = o.image_error;
  r.adaptive = o.adaptive;
  r.min_samples = o.min_spp;
  r.estimate_error = o.stats_channels;
  r.russian_roulette = o.roulette == roulette_name(true);  // CLI11 checked it is on or off
  if (!o.passes.empty()) {
    try {
      r.passes = parse_passes(o.passes);
    } catch (const InvalidInput& e) {
      throw InvalidInput(std::string("--passes: ") + e.what());
    }
  }
  return r;
}

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

void add_sampling_options(CLI::App* cmd, RenderOptions& o) {
  cmd->add_option("--spp", o.spp, "Samples per pixel (default: the scene's)");
  cmd->add_option("--depth", o.depth,
                  "Maximum rays per path, 0 to " + std::to_string(limits::kMaxDepth) +
                      " (default: the scene's)");
  cmd->add_option("--seed", o.seed, "Seed of the sample streams, 0 to 2^64-1")
      ->check(kNotNegative)
      ->capture_default_str();
  cmd->add_option("--threads", o.threads,
                  "Worker threads, 0 (all cores) to " + std::to_string(limits::kMaxThreads))
      ->capture_default_str();
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

}  // namespace

// --help lists the options in groups, in this order: 40 options in one list were a wall.
void group_options(CLI::App* cmd) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> groups = {
      {"Scene", {"--scene", "--list-scenes", "--like", "--scene-seed"}},
      {"Output",
       {"-o", "--width", "--height", "--crop", "--passes", "--stats-channels", "--reproducible",
        "-q", "--summary-json", "--preview", "--display"}},
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

RenderOptionHandles add_render_options(CLI::App* cmd, RenderOptions& o) {
  RenderOptionHandles handles;
  handles.scene = add_scene_options(cmd, o);
  handles.output = add_image_options(cmd, o);
  add_sampling_options(cmd, o);
  add_run_options(cmd, o);
  add_camera_options(cmd, o);
  group_options(cmd);
  return handles;
}

JobRequest job_request_of(const RenderOptions& o, bool scene_named, bool output_given, int rank,
                          int ranks) {
  JobRequest job;
  job.request = request_of(o);  // a bad --sampler or --accel before anything else
  job.scene_file = o.scene_file;
  job.scene = o.scene, job.scene_seed = o.scene_seed, job.scene_named = scene_named;
  job.output = o.output, job.output_given = output_given;
  job.sample_range = o.sample_range, job.part = o.part;
  job.rank = rank, job.ranks = ranks;
  job.stats_channels = o.stats_channels;
  if (!o.like.empty()) job.other_inputs.push_back(o.like);
  return job;
}

}  // namespace rtiow
