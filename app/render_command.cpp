#include "app/render_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "app/checkpoint_session.h"
#include "app/cli_checks.h"
#include "app/image_request.h"
#include "app/interrupt.h"
#include "app/mpi_session.h"
#include "app/output_lock.h"
#include "app/progress_display.h"
#include "core/io/atomic_file.h"
#include "core/io/image_backend.h"
#include "core/io/image_output.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/parallel/thread_count.h"
#include "core/render/render.h"
#include "core/render/render_loop.h"
#include "core/render/render_metadata.h"
#include "core/render/render_part.h"
#include "core/render/render_request.h"
#include "core/render/render_statistics.h"
#include "core/render/sample_share.h"
#include "core/scene/builtin_scenes.h"
#include "core/scene/scene_file.h"

namespace rtiow {
namespace {

struct RenderOptions {
  std::string scene_file;
  std::string like;  // an image whose recorded request this render repeats
  std::string scene = "cover";
  std::uint64_t scene_seed = 1;
  bool list_scenes = false;
  std::string output;
  std::optional<int> width, height, spp, depth;
  std::uint64_t seed = RenderRequest{}.seed;
  int threads = RenderRequest{}.threads;
  std::string accel = to_string(RenderRequest{}.accel);
  std::string fresnel;  // empty: as the scene says
  double time_limit = 0.0;
  std::string sampler = to_string(RenderRequest{}.sampler);
  double target_error = 0.0;
  double image_error = 0.0;
  bool adaptive = false;
  int min_spp = RenderRequest{}.min_samples;
  bool stats_channels = false;
  bool quiet = false;
  bool reproducible = false;
  double checkpoint_seconds = 60.0;  // 0: none
  bool resume = false;
  bool restart = false;
  bool keep_state = false;
  std::string sample_range;  // "A:B": render a share of the samples into a part file
  std::string part;          // "i/n": the i-th of n equal shares
  std::vector<double> lookfrom, lookat, vup;
  std::optional<double> vfov, aperture, focus_distance;
};

Vec3d to_vec3(const std::vector<double>& v) {
  return {v[0], v[1], v[2]};
}

// The options as a request to the core, which gives them their meaning.
RenderRequest request_of(const RenderOptions& o) {
  RenderRequest r;
  r.width = o.width, r.height = o.height;
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
  return r;
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
  char text[192];
  if (is_adaptive(s)) {
    const auto [least, most] = std::minmax_element(r.pixel_samples.begin(), r.pixel_samples.end());
    char goal[128] = "adaptive";
    // An error-driven render that stopped at its cap says so, and how far it got.
    if (const auto* t = std::get_if<PixelErrorTarget>(&s.samples)) {
      if (r.pixels_above_target > 0) {
        std::snprintf(goal, sizeof goal, "target error %g not reached by %llu pixels at %d spp",
                      t->error, static_cast<unsigned long long>(r.pixels_above_target), t->most);
      } else {
        std::snprintf(goal, sizeof goal, "target error %g", t->error);
      }
    }
    if (const auto* i = std::get_if<ImageErrorTarget>(&s.samples)) {
      if (r.estimated_image_error > i->error && !r.stopped && !r.time_limited) {
        std::snprintf(goal, sizeof goal, "image error %g not reached: %.3g at %d spp", i->error,
                      r.estimated_image_error, i->most);
      } else {
        std::snprintf(goal, sizeof goal, "image error %g", i->error);
      }
    }
    std::snprintf(text, sizeof text, "%u-%u spp (mean %.1f, %s)", *least, *most, mean_samples(r),
                  goal);
  } else {
    std::snprintf(text, sizeof text, "%d spp", r.samples_completed);
  }
  return text;
}

Scene load_scene(const RenderOptions& o, bool scene_option_given) {
  if (o.scene_file.empty()) return make_builtin_scene(o.scene, o.scene_seed);
  if (scene_option_given) {
    throw InvalidInput("give a scene file or --scene, not both");
  }
  // `rtiow render cover`, as `rtiow scene cover` takes it: the built-in scene is --scene cover.
  std::error_code no_file;
  if (!std::filesystem::exists(o.scene_file, no_file) && is_builtin_scene_name(o.scene_file)) {
    throw InvalidInput("no scene file " + quote_value(o.scene_file) +
                       "; the built-in scene is rendered with --scene " + o.scene_file);
  }
  return load_scene_file(o.scene_file);
}

// The output: as given (an empty -o is an error, not the default), or named after the scene.
std::string output_path(const RenderOptions& o, bool output_given, const Scene& scene) {
  if (output_given && o.output.empty()) throw InvalidInput("-o/--output: the path is empty");
  return output_given ? o.output : default_output(scene.name);
}

// "A:B" or "i/n" into the share of samples this process renders; nothing when neither.
// The job is the settings' fixed sample count; a share must lie within it.
void apply_share(const RenderOptions& o, const std::string& output, RenderSettings& settings) {
  if (o.sample_range.empty() && o.part.empty()) return;
  if (!o.sample_range.empty() && !o.part.empty()) {
    throw InvalidInput("give --sample-range or --part, not both");
  }
  if (image_format(output) == nullptr || !image_format(output)->extra_channels) {
    throw InvalidInput("output " + quote_value(output) +
                       ": a share of a render is written as a part file, which must be .exr");
  }
  const std::uint64_t total =
      shareable_samples(settings, o.part.empty() ? "--sample-range" : "--part");
  restrict_to(
      o.part.empty() ? parse_sample_range(o.sample_range, total) : parse_part(o.part, total),
      settings);
}

// Under mpirun: this rank's equal share of the samples of every pixel.
void apply_rank_share(const RenderOptions& o, const MpiSession& mpi, RenderSettings& settings) {
  if (!mpi.distributed()) return;
  if (!o.sample_range.empty() || !o.part.empty()) {
    throw InvalidInput(
        "--sample-range and --part are for separate jobs; under mpirun the ranks "
        "share the samples themselves");
  }
  const std::uint64_t total = shareable_samples(settings, "mpirun");
  const auto ranks = std::uint64_t(mpi.size());
  if (total < ranks) {
    throw InvalidInput(std::to_string(total) + " samples per pixel cannot be shared by " +
                       std::to_string(ranks) + " ranks");
  }
  restrict_to(equal_share(total, std::uint64_t(mpi.rank()), ranks), settings);
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
  const char* adaptive = o.target_error > 0  ? "--target-error"
                         : o.image_error > 0 ? "--image-error"
                         : o.adaptive        ? "--adaptive"
                                             : nullptr;
  if (adaptive && (!o.sample_range.empty() || !o.part.empty() || mpi.distributed())) {
    throw InvalidInput(std::string(adaptive) +
                       " needs all of a pixel's samples in one process: it cannot be combined "
                       "with --sample-range, --part or mpirun");
  }

  // (A part with --stats-channels keeps two replicates, so that 'rtiow merge --stats-channels'
  // can write the whole render's variances; the part file holds its exact spreads, not channels.)
}

// A render as the options ask for it: the scene, the settings of this process's share, and
// where it goes. Everything is checked here, before any work.
struct Job {
  Scene scene;
  RenderSettings settings;
  std::string output;
  std::uint64_t samples_asked = 0;  // a shared job's whole count, before it is cut
  bool share = false;               // written as a part file
};

std::vector<std::string> input_files(const RenderOptions& o) {
  std::vector<std::string> inputs;
  if (!o.scene_file.empty()) inputs.push_back(o.scene_file);
  if (!o.like.empty()) inputs.push_back(o.like);
  return inputs;
}

// `like`: the request of the --like image, whose scene is checked against its digest.
Job prepare_job(const RenderOptions& o, bool scene_option_given, bool output_given,
                const MpiSession& mpi, const ImageRequest* like) {
  // Cheap checks of the output first, so a bad -o is refused before a large scene loads.
  if (output_given) check_output_path(output_path(o, output_given, Scene{}), input_files(o));
  Job job;
  const RenderRequest request = request_of(o);  // a bad --sampler or --accel before the load
  // A generated scene is built in parallel: within --threads, as the render is (a count out
  // of range is refused by name once the request is resolved).
  const int threads = o.threads >= 0 && o.threads <= limits::kMaxThreads ? o.threads : 0;
  Scene scene = with_threads(threads, [&] { return load_scene(o, scene_option_given); });
  if (like) check_scene_of_image(*like, scene, o.like);
  job.output = output_path(o, output_given, scene);
  // The whole job, resolved and checked before it is cut into a share.
  ResolvedRender resolved = resolve(std::move(scene), request);
  job.scene = std::move(resolved.scene);
  job.settings = resolved.settings;
  // A shared job's whole count, which the shares are cut from and which combines them again.
  if (const auto* fixed = std::get_if<FixedSamples>(&job.settings.samples)) {
    job.samples_asked = std::uint64_t(fixed->per_pixel);
  }
  check_adaptive_options(o, job.output, mpi);
  job.share = !o.sample_range.empty() || !o.part.empty();
  apply_share(o, job.output, job.settings);
  apply_rank_share(o, mpi, job.settings);
  check_image_output(job.output, input_files(o), o.stats_channels);
  validate(job.scene, job.settings);
  return job;
}

// Renders with Ctrl-C handling and, unless quiet, a progress display (under MPI on rank 0,
// which shows its own share: it moves with the others').
RenderResult render_with_progress(const RenderOptions& o, const Job& job, const MpiSession& mpi,
                                  RenderProgress& progress, const Checkpointing* checkpointing) {
  std::unique_ptr<ProgressDisplay> display;
  if (!o.quiet && mpi.rank() == 0) {
    // Adaptive sampling and an open-ended time limit have no total to show progress against.
    const RenderSettings& s = job.settings;
    const auto* fixed = std::get_if<FixedSamples>(&s.samples);
    display = std::make_unique<ProgressDisplay>(
        progress,
        fixed ? std::uint64_t(s.width) * std::uint64_t(s.height) * std::uint64_t(fixed->per_pixel)
              : 0);
  }
  return render(job.scene, job.settings, &progress, checkpointing);
}

// Under MPI, rank 0 adds every rank's exact sums (and, for the variances, `spreads`) into the
// image of one process with all the samples. Returns false on the other ranks, which have nothing
// left to do.
bool gather_ranks(const MpiSession& mpi, Job& job, RenderResult& result, bool spreads) {
  const std::uint64_t done = mpi.reduce_sum(std::uint64_t(result.samples_completed));
  result.rays_traced = mpi.reduce_sum(result.rays_traced);
  result.render_seconds = mpi.reduce_max(result.render_seconds);
  mpi.reduce_sums(result.sums, spreads ? &result.spreads : nullptr);
  if (mpi.rank() != 0) return false;
  result.stopped = done < job.samples_asked;
  complete_from_shares(done, result);
  restore_whole_job(job.samples_asked, job.settings);
  return true;
}

void write_result(const RenderOptions& o, const Job& job, const RenderResult& result) {
  Metadata metadata = render_metadata(job.scene, job.settings, result, o.reproducible);
  if (!o.scene_file.empty()) metadata.emplace_back(metadata_key::kSceneFile, o.scene_file);
  if (!job.share) {
    write_image(job.output, result.film, metadata,
                o.stats_channels ? statistics_channels(result) : std::vector<ExtraChannel>{});
    return;
  }
  RenderPart part;
  part.width = job.settings.width, part.height = job.settings.height;
  part.first_sample = job.settings.first_sample;
  part.samples = std::uint64_t(result.samples_completed);
  part.job_samples = job.samples_asked;
  part.digest = render_digest(job.scene, job.settings);
  part.metadata = metadata;
  part.sums = result.sums;  // copied: kept in the result, should the write fail
  part.spreads = result.spreads;
  write_part(job.output, part);
}

// "rendered cover 1200x800, 500 spp, depth 50, embree, 2 threads: ... -> path"
void print_summary(const Job& job, const RenderResult& result, const MpiSession& mpi) {
  const RenderSettings& s = job.settings;
  const double rays = double(result.rays_traced);
  const int threads = thread_count(s.threads);  // the threads used (core/parallel/thread_count.h)
  const std::string ranks = mpi.distributed() ? std::to_string(mpi.size()) + " ranks x " : "";
  std::fprintf(stderr,
               "rendered %s %dx%d, %s, depth %d, %s, %s%d thread%s: %.2f s, %.3g rays, "
               "%.2f Mrays/s -> %s\n",
               job.scene.name.c_str(), s.width, s.height, describe_samples(s, result).c_str(),
               s.max_depth, to_string(s.accel).c_str(), ranks.c_str(), threads,
               threads == 1 ? "" : "s", result.render_seconds, rays,
               rays / result.render_seconds * 1e-6, one_line(job.output).c_str());
}

// The checkpoint of this process's render: none under mpirun (each rank holds only its
// share), where --resume is refused.
std::unique_ptr<CheckpointSession> open_checkpoint(const RenderOptions& o, const Job& job,
                                                   const MpiSession& mpi) {
  if (mpi.distributed()) {
    if (o.resume) throw InvalidInput("--resume is for a render in one process, not under mpirun");
    return nullptr;
  }
  if (o.resume && o.restart) throw InvalidInput("give --resume or --restart, not both");
  CheckpointOptions options;
  options.interval_seconds = o.checkpoint_seconds;
  options.resume = o.resume, options.restart = o.restart;
  options.keep_state = o.keep_state, options.quiet = o.quiet;
  if (o.keep_state && o.checkpoint_seconds <= 0.0) {
    throw InvalidInput("--keep-state keeps the render's checkpoint: it needs --checkpoint above 0");
  }
  auto session = std::make_unique<CheckpointSession>(job.output, job.scene, job.settings, options);
  if (session->resumed_from() && !o.quiet) {
    std::fprintf(stderr, "rtiow: resuming from %s (%u spp done)\n",
                 quote_value(session->path()).c_str(), *session->resumed_from());
  }
  return session;
}

// Writes the image; if that fails after the render, keeps the render's state and says where.
void write_or_keep(const RenderOptions& o, const Job& job, const RenderResult& result,
                   CheckpointSession* checkpoint) {
  try {
    write_result(o, job, result);
  } catch (const InvalidInput&) {
    throw;
  } catch (const std::exception& e) {
    if (!checkpoint || !checkpoint->checkpointing()) throw;  // --checkpoint 0: nothing kept
    const std::string what = dynamic_cast<const std::bad_alloc*>(&e)
                                 ? "out of memory writing " + quote_value(job.output, kWholePath)
                                 : std::string(e.what());
    try {
      checkpoint->image_lost(state_of(result));
    } catch (const std::bad_alloc&) {  // no memory for a copy of the state: said below
    }
    if (!checkpoint->holds_the_render()) {
      throw std::runtime_error(
          what + "; and the render's state could not be kept" +
          (checkpoint->failure().empty() ? std::string() : " (" + checkpoint->failure() + ")"));
    }
    throw std::runtime_error(what + "; the render is kept in " +
                             quote_value(checkpoint->kept_at(), kWholePath) + ": " +
                             checkpoint->how_to_continue() + " to write it");
  }
  if (checkpoint) checkpoint->image_written();
}

// A uniform render that asks for more than a day of work on a 2-core machine (the cover runs
// at about 5e6 samples per second there) says so before it starts, and how to bound it: the
// count is accepted (a farm or a long night may mean it), but not silently.
void note_long_request(const Job& job) {
  const RenderSettings& s = job.settings;
  const auto* fixed = std::get_if<FixedSamples>(&s.samples);
  if (!fixed || s.time_limit_seconds > 0) return;
  const double samples = double(s.width) * double(s.height) * double(fixed->per_pixel);
  constexpr double kSamplesPerSecond = 5e6, kDay = 86400;
  const double days = samples / kSamplesPerSecond / kDay;
  if (days < 1) return;
  std::fprintf(stderr,
               "rtiow: note: %d spp at %dx%d is %.3g samples, about %.3g days on a 2-core machine; "
               "a signal (Ctrl-C) keeps what is done and --resume continues it, --time-limit "
               "bounds it\n",
               fixed->per_pixel, s.width, s.height, samples, days);
}

// A signal that arrived where the render could not stop for it (the scene's load, the final
// writes) ends the command once they are done, in rtiow's words; 0 if none did.
int interrupted_outside_render(const char* when) {
  const int signal = InterruptGuard::signal_received();
  if (signal == 0) return 0;
  std::fprintf(stderr, "rtiow: interrupted (signal %d) %s\n", signal, when);
  return 128 + signal;
}

// The work a killed render left beside the output: its temporaries (the lock is held, so no
// live rtiow writes them).
void remove_leftovers(const std::string& output, bool quiet) {
  const int removed =
      remove_stale_temporaries(output) + remove_stale_temporaries(checkpoint_path(output));
  if (removed > 0 && !quiet) {
    std::fprintf(stderr, "rtiow: removed %d temporar%s an interrupted rtiow left beside %s\n",
                 removed, removed == 1 ? "y" : "ies", quote_value(output).c_str());
  }
}

int run_render(const RenderOptions& o, bool scene_option_given, bool output_given,
               const MpiSession& mpi, const ImageRequest* like) {
  if (o.list_scenes) return mpi.rank() == 0 ? list_scenes() : 0;
  // From the scene's load to the last write, a signal asks the command to stop gracefully.
  RenderProgress progress;
  const InterruptGuard interrupt(progress.stop_requested);
  Job job = prepare_job(o, scene_option_given, output_given, mpi, like);
  if (const int code = interrupted_outside_render("before the render began; nothing was written")) {
    return code;
  }
  if (mpi.rank() == 0) note_long_request(job);
  // Rank 0 writes the output (and, alone, keeps a checkpoint).
  const std::optional<OutputLock> lock =
      mpi.rank() == 0 ? std::make_optional<OutputLock>(job.output) : std::nullopt;
  if (lock) remove_leftovers(job.output, o.quiet);
  const std::unique_ptr<CheckpointSession> checkpoint = open_checkpoint(o, job, mpi);
  // The image library loads on a second thread while the render runs (rank 0 writes), unless
  // rtiow encodes the format itself (PNG): then it is never loaded.
  if (mpi.rank() == 0) {
    start_parallel_runtime();
    const ImageFormat* format = image_format(job.output);
    if (!format || !format->own_encoder) preload_image_backend();
  }
  RenderResult result = render_with_progress(o, job, mpi, progress,
                                             checkpoint ? checkpoint->checkpointing() : nullptr);
  if (mpi.distributed() && !gather_ranks(mpi, job, result, o.stats_channels)) return 0;
  write_or_keep(o, job, result, checkpoint.get());
  if (checkpoint) checkpoint->warn_where_kept();  // even when quiet
  if (result.stopped) {
    // What was asked: a count, a budget (--adaptive), a cap, or nothing but a time limit.
    const RenderSettings& s = job.settings;
    std::string asked;
    if (const std::optional<int> spp = spp_option(s.samples)) {
      const bool budget = std::holds_alternative<AdaptiveBudget>(s.samples);
      const bool cap = std::holds_alternative<PixelErrorTarget>(s.samples) ||
                       std::holds_alternative<ImageErrorTarget>(s.samples);
      asked = (budget ? " (of a budget of "
               : cap  ? " (of a cap of "
                      : " (of ") +
              std::to_string(*spp) + (budget || cap ? " spp)" : " asked)");
    }
    const std::string kept = checkpoint && checkpoint->holds_the_render()
                                 ? "; the render is kept in " +
                                       quote_value(checkpoint->kept_at(), kWholePath) + " (" +
                                       checkpoint->how_to_continue() + " to continue it)"
                                 : "";
    std::fprintf(stderr, "rtiow: interrupted: wrote %s%s to %s%s\n",
                 describe_samples(s, result).c_str(), asked.c_str(), one_line(job.output).c_str(),
                 kept.c_str());
    return 128 + InterruptGuard::signal_received();
  }
  if (!o.quiet) print_summary(job, result, mpi);
  return interrupted_outside_render("after the render ended; the image is complete");
}

}  // namespace

namespace {

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
  return output_option;
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
                  "Sampler: sobol (one Owen-scrambled Sobol point for pixel, lens and first "
                  "bounce, padded Sobol for later bounces: 2.3-5.4x lower relMSE at equal time "
                  "on the built-in scenes), independent (the book's) or padded-sobol (every 1D "
                  "and 2D dimension its own scrambled Sobol sequence)")
      ->check(CLI::IsMember({to_string(SamplerKind::Independent), to_string(SamplerKind::Sobol),
                             to_string(SamplerKind::PaddedSobol)}))
      ->capture_default_str();
  cmd->add_option("--target-error", o.target_error,
                  "Adaptive sampling: each pixel stops once its relative standard error is below "
                  "this (e.g. 0.05); --spp is then the most a pixel takes (default " +
                      std::to_string(kDefaultErrorDrivenMaxSpp) + ")")
      ->check(kFiniteNotNegative);
  cmd->add_option("--image-error", o.image_error,
                  "Adaptive sampling: stop once the image's estimated relative RMS error is "
                  "below this (e.g. 0.02; it aims at 0.92 of it), giving each pixel samples in "
                  "proportion to "
                  "sqrt(variance / cost); --spp is then the most a pixel takes (default " +
                      std::to_string(kDefaultErrorDrivenMaxSpp) + ")")
      ->check(kFiniteNotNegative);
  cmd->add_flag("--adaptive", o.adaptive,
                "Adaptive sampling on a budget: the time of --spp uniform samples (or "
                "--time-limit), spread over the pixels in proportion to sqrt(variance / cost), "
                "which gives the lowest image error for the time");
  cmd->add_option("--min-spp", o.min_spp,
                  "Adaptive sampling: samples every pixel takes before it may stop (at least 2)")
      ->check(CLI::Range(2, std::numeric_limits<int>::max()))
      ->capture_default_str();
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
      ->delimiter(',');
  cmd->add_option("--lookat", o.lookat, "Point the camera looks at x,y,z")
      ->expected(3)
      ->delimiter(',');
  cmd->add_option("--vup", o.vup, "Camera up vector x,y,z")->expected(3)->delimiter(',');
  cmd->add_option("--vfov", o.vfov, "Vertical field of view in degrees, in (0, 180)");
  cmd->add_option("--aperture", o.aperture, "Lens diameter (0: pinhole)");
  cmd->add_option("--focus-dist", o.focus_distance, "Distance to the plane in focus");
}

}  // namespace

std::function<int()> add_render_command(CLI::App& app, const MpiSession& mpi) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Render a scene file or a built-in scene to an image (with no options: the book's cover "
      "at its final settings, to cover.png)");
  CLI::Option* scene_option = add_scene_options(cmd, *options);
  CLI::Option* output_option = add_image_options(cmd, *options);
  add_sampling_options(cmd, *options);
  add_run_options(cmd, *options);
  add_camera_options(cmd, *options);
  return [options, cmd, scene_option, output_option, &mpi] {
    if (!cmd->parsed()) return -1;
    std::optional<ImageRequest> like;
    bool scene_chosen = false;  // by the user, over the --like image's
    if (!options->like.empty()) {
      like = read_image_request(options->like);
      scene_chosen = apply_image_request(*like, *cmd);
    }
    return run_render(*options, scene_option->count() > 0, output_option->count() > 0, mpi,
                      like && !scene_chosen ? &*like : nullptr);
  };
}

}  // namespace rtiow
