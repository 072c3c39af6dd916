#include "core/render/render_job.h"

#include <filesystem>
#include <system_error>
#include <utility>
#include <variant>

#include "core/denoise/denoiser.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/limits/setting_name.h"
#include "core/parallel/cancellation.h"
#include "core/parallel/thread_count.h"
#include "core/render/render.h"
#include "core/render/render_part.h"
#include "core/render/render_statistics.h"
#include "core/render/sample_share.h"
#include "core/scene/builtin_scenes.h"
#include "core/scene_file/scene_file.h"

namespace rtiow {

Scene load_job_scene(const JobRequest& r) {
  if (r.scene_file.empty()) return make_builtin_scene(r.scene, r.scene_seed);
  if (r.scene_named) throw InvalidInput("give a scene file or " + setting("scene") + ", not both");
  // `rtiow render cover`, as `rtiow scene cover` takes it: the built-in scene is --scene cover.
  std::error_code no_file;
  if (!std::filesystem::exists(r.scene_file, no_file) && is_builtin_scene_name(r.scene_file)) {
    throw InvalidInput("no scene file " + quote_value(r.scene_file) +
                       "; the built-in scene is rendered with " + setting("scene", r.scene_file));
  }
  return load_scene_file(r.scene_file);
}

namespace {

// The output: as given (an empty -o is an error, not the default), or named after the scene.
std::string output_path(const JobRequest& r, const Scene& scene) {
  if (r.output_given && r.output.empty())
    throw InvalidInput(setting("output") + ": the path is empty");
  return r.output_given ? r.output : safe_file_stem(scene.name) + ".png";
}

// "A:B" or "i/n" into the share of samples this process renders; nothing when neither.
// The job is the settings' fixed sample count; a share must lie within it.
void apply_share(const JobRequest& r, const std::string& output, RenderSettings& settings) {
  if (r.sample_range.empty() && r.part.empty()) return;
  if (!r.sample_range.empty() && !r.part.empty()) {
    throw InvalidInput("give " + setting("sample_range") + " or " + setting("part") + ", not both");
  }
  if (image_format(output) == nullptr || !image_format(output)->extra_channels) {
    throw InvalidInput("output " + quote_value(output) +
                       ": a share of a render is written as a part file, which must be .exr");
  }
  const std::uint64_t total =
      shareable_samples(settings, setting(r.part.empty() ? "sample_range" : "part"));
  restrict_to(
      r.part.empty() ? parse_sample_range(r.sample_range, total) : parse_part(r.part, total),
      settings);
}

// Under mpirun: this rank's equal share of the samples of every pixel.
void apply_rank_share(const JobRequest& r, RenderSettings& settings) {
  if (r.ranks <= 1) return;
  if (!r.sample_range.empty() || !r.part.empty()) {
    throw InvalidInput(setting("sample_range") + " and " + setting("part") +
                       " are for separate jobs; under mpirun the ranks share the samples "
                       "themselves");
  }
  const std::uint64_t total = shareable_samples(settings, "mpirun");
  const auto ranks = std::uint64_t(r.ranks);
  if (total < ranks) {
    throw InvalidInput(std::to_string(total) + " samples per pixel cannot be shared by " +
                       std::to_string(ranks) + " ranks");
  }
  restrict_to(equal_share(total, std::uint64_t(r.rank), ranks), settings);
}

// Adaptive sampling decides each pixel's stop on all its samples, so it cannot be split
// into shares; the statistics channels need a format with room for them.
void check_adaptive_options(const JobRequest& r, const std::string& output) {
  const ImageFormat* format = image_format(output);
  if (r.stats_channels && format && !format->extra_channels) {
    throw InvalidInput(setting("stats_channels") + ": output " + quote_value(output) +
                       " must be .exr to hold the spp and variance channels");
  }
  const RenderRequest& q = r.request;
  if (q.passes.any() && format && !format->extra_channels) {
    throw InvalidInput(setting("passes") + ": output " + quote_value(output) +
                       " must be .exr to hold the " + to_string(q.passes) +
                       " channels beside the image");
  }
  const char* adaptive = q.target_error > 0  ? "target_error"
                         : q.image_error > 0 ? "image_error"
                         : q.adaptive        ? "adaptive"
                                             : nullptr;
  if (adaptive && (!r.sample_range.empty() || !r.part.empty() || r.ranks > 1)) {
    throw InvalidInput(setting(adaptive) +
                       " needs all of a pixel's samples in one process: it cannot be combined "
                       "with " +
                       setting("sample_range") + ", " + setting("part") + " or mpirun");
  }
  // (A part with --stats-channels keeps two replicates, so that 'rtiow merge --stats-channels'
  // can write the whole render's variances; the part file holds its exact spreads, not channels.)
}

// A pixel's error target would judge the noisy pixels, not the denoised image; the image's
// error target judges the denoised image (core/render/denoised_rounds.h).
void check_denoise_options(const JobRequest& r) {
  if (!r.denoise) return;
  if (r.request.target_error > 0) {
    throw InvalidInput(setting("denoise") + " with " + setting("target_error") +
                       ": the target would be each noisy pixel's error, not the denoised "
                       "image's; give " +
                       setting("image_error") + " (the denoised image's error), a sample count, " +
                       setting("time_limit") + " or " + setting("adaptive") + " instead");
  }
  // (A count below 1 is refused as any render's is, in its own words.)
  if (r.request.spp && *r.request.spp == 1 && !r.request.adaptive) {
    throw InvalidInput(setting("denoise") +
                       " needs at least 2 spp, one in each half it compares (" +
                       setting("spp", std::to_string(*r.request.spp)) + ")");
  }
}

}  // namespace

RenderRequest job_render_request(const JobRequest& r) {
  check_denoise_options(r);
  RenderRequest q = r.request;
  if (r.denoise) {
    q.estimate_error = true, q.passes = {true, true, true};
    q.image_error_denoised = q.image_error > 0;
  }
  return q;
}

std::vector<std::string> input_files(const JobRequest& r) {
  std::vector<std::string> inputs;
  if (!r.scene_file.empty()) inputs.push_back(r.scene_file);
  inputs.insert(inputs.end(), r.other_inputs.begin(), r.other_inputs.end());
  return inputs;
}

RenderJob prepare_job(const JobRequest& r) {
  // Cheap checks of the output first, so a bad -o is refused before a large scene loads.
  if (r.output_given) check_output_path(output_path(r, Scene{}), input_files(r));
  // A generated scene is built in parallel: within the request's threads, as the render is (a
  // count out of range refused first, as cheaply as a bad -o).
  check_thread_count(r.request.threads);
  Scene scene = with_threads(r.request.threads, [&] { return load_job_scene(r); });
  if (r.check_loaded_scene) r.check_loaded_scene(scene);
  return prepare_job(r, std::move(scene));
}

RenderJob prepare_job(const JobRequest& r, Scene scene) {
  RenderJob job;
  job.output = output_path(r, scene);
  // The whole job, resolved and checked before it is cut into a share.
  ResolvedRender resolved = resolve(std::move(scene), job_render_request(r));
  job.scene = std::move(resolved.scene);
  job.settings = resolved.settings;
  // A shared job's whole count, which the shares are cut from and which combines them again.
  if (const auto* fixed = std::get_if<FixedSamples>(&job.settings.samples)) {
    job.samples_asked = std::uint64_t(fixed->per_pixel);
  }
  check_adaptive_options(r, job.output);
  job.share = !r.sample_range.empty() || !r.part.empty();
  apply_share(r, job.output, job.settings);
  apply_rank_share(r, job.settings);
  check_image_output(job.output, input_files(r), r.stats_channels || r.request.passes.any());
  validate(job.scene, job.settings);
  return job;
}

std::optional<DenoisedImage> denoise_for_output(const JobRequest& r, const RenderJob& job,
                                                const RenderResult& result,
                                                WorkProgress* progress) {
  if (job.share || !r.denoise || !why_not_denoised(result).empty()) return std::nullopt;
  try {
    return denoised_image(result, DenoiseControl{final_write_stop_requested, progress});
  } catch (const DenoiseCancelled&) {
    // An end asked for while it denoised (core/parallel/cancellation.h): what was rendered is
    // written now, neither lost nor kept waiting for the denoiser.
    return std::nullopt;
  }
}

void write_job_result(const JobRequest& r, const RenderJob& job, const RenderResult& result,
                      const Metadata& metadata, const DenoisedImage* denoised) {
  if (job.share) {
    write_part(job.output, make_part(job.scene, job.settings, job.samples_asked, result, metadata),
               result.sums);
    return;
  }
  const ImageFormat* format = image_format(job.output);
  const bool extra = format && format->extra_channels;
  // The image as rendered (the passes --denoise asked for go where the format holds them).
  const auto write_noisy = [&] {
    write_image(job.output, result.film, metadata,
                extra ? image_channels(result, r.stats_channels, job.settings.passes)
                      : std::vector<ExtraChannel>{},
                frame_placement(job.settings));
  };
  // Not denoised: not asked, a render stopped (or time-limited) before each half had a sample,
  // or an end asked for while it denoised.
  if (!denoised) {
    write_noisy();
    return;
  }
  Metadata with_figures = metadata;
  DenoisedOutput output = denoised_output(*denoised, extra, with_figures);
  std::vector<ExtraChannel> channels;
  if (extra) {
    channels = std::move(output.channels);
    for (ExtraChannel& c : image_channels(result, r.stats_channels, job.settings.passes))
      channels.push_back(std::move(c));
  }
  write_image(job.output, output.image, with_figures, channels, frame_placement(job.settings));
}

}  // namespace rtiow
