#include "core/session/render_summary.h"

#include "core/io/summary_json.h"
#include "core/parallel/thread_count.h"
#include "core/render/render_outcome.h"
#include "core/render/render_statistics.h"
#include "core/sampling/sampler.h"
#include "core/session/summary_members.h"

namespace rtiow {
namespace {

// The error-driven modes' goal: what was asked and whether it was reached; null for the others.
void write_error_target(JsonWriter& j, const RenderSettings& s, const RenderResult& result) {
  if (const auto* image = std::get_if<ImageErrorTarget>(&s.samples)) {
    j.begin_object();
    j.key("kind").string(image->denoised ? "denoised image" : "image");
    j.key("asked").number(image->error);
    j.key("reached").boolean(error_target_reached(s, result));
    j.end();
  } else if (const auto* pixel = std::get_if<PixelErrorTarget>(&s.samples)) {
    j.begin_object();
    j.key("kind").string("pixel");
    j.key("asked").number(pixel->error);
    j.key("pixels_above").whole(result.pixels_above_target);
    j.key("reached").boolean(error_target_reached(s, result));
    j.end();
  } else {
    j.null();
  }
}

// How many samples each pixel took, and what was asked.
void write_samples(JsonWriter& j, const RenderSettings& s, const RenderOutcome& outcome) {
  write_spp_member(j, outcome.least, outcome.most, outcome.mean, spp_option(s.samples));
  j.key("samples").string(outcome.samples);
  outcome.stopped.empty() ? j.key("stopped").null() : j.key("stopped").string(outcome.stopped);
}

// The render's own members, into an object already begun.
void write_render_members(JsonWriter& j, const std::string& scene, const RenderSettings& s,
                          const RenderResult& result, int ranks, const std::string* output,
                          const std::optional<DenoiseFigures>& denoised) {
  const double seconds = result.render_seconds;
  output ? j.key("output").string(*output) : j.key("output").null();
  j.key("scene").string(scene);
  j.key("width").whole(s.width);
  j.key("height").whole(s.height);
  j.key("crop");
  if (s.crop) {
    j.begin_array().whole(s.crop->x0).whole(s.crop->y0).whole(s.crop->x1).whole(s.crop->y1).end();
  } else {
    j.null();
  }
  write_passes_member(j, s.passes);
  j.key("depth").whole(s.max_depth);
  j.key("accelerator").string(to_string(s.accel));
  j.key("sampler").string(to_string(s.sampler));
  j.key("seed").whole(s.seed);
  j.key("threads").whole(thread_count(s.threads));
  j.key("ranks").whole(ranks);
  write_samples(j, s, describe_outcome(s, result));
  j.key("render_seconds").number(seconds);
  j.key("judging_seconds").number(result.judging_seconds);
  j.key("build_seconds").number(result.build_seconds);
  j.key("rays").whole(result.rays_traced);
  j.key("mrays_per_second").number(tracing_mrays_per_second(result));
  // Every render's estimate of its image error, and the error-driven modes' goal.
  write_error_member(j, result.error_estimate, result.estimated_image_error,
                     [&](JsonWriter& w) { write_error_target(w, s, result); });
  write_denoise_member(j, denoised);
}

}  // namespace

std::string render_summary_json(const RenderJob& job, const RenderResult& result, int ranks,
                                int exit_code, bool image_written,
                                const std::optional<DenoiseFigures>& denoised) {
  JsonWriter j = begin_summary("render", exit_code);
  write_render_members(j, job.scene.name, job.settings, result, ranks,
                       image_written ? &job.output : nullptr, denoised);
  return summary_text(j);
}

std::string render_members_json(const std::string& scene, const RenderSettings& settings,
                                const RenderResult& result, const std::string* output,
                                const std::optional<DenoiseFigures>& denoised) {
  JsonWriter j;
  j.begin_object();
  write_render_members(j, scene, settings, result, 1, output, denoised);
  j.end();
  return j.text();
}

}  // namespace rtiow
