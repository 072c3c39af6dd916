#include "core/session/render_summary.h"

#include "core/io/summary_json.h"
#include "core/parallel/thread_count.h"
#include "core/render/render_outcome.h"
#include "core/render/render_statistics.h"
#include "core/sampling/sampler.h"

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
  j.key("spp").begin_object();
  j.key("least").whole(outcome.least);
  j.key("most").whole(outcome.most);
  j.key("mean").number(outcome.mean);
  const std::optional<int> asked = spp_option(s.samples);
  asked ? j.key("asked").whole(*asked) : j.key("asked").null();
  j.end();
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
  j.key("passes").begin_array();
  if (s.passes.albedo) j.string("albedo");
  if (s.passes.normal) j.string("normal");
  if (s.passes.depth) j.string("depth");
  j.end();
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
  j.key("error").begin_object();
  if (result.error_estimate != ErrorEstimate::None) {
    j.key("estimated").number(result.estimated_image_error);
  } else {
    j.key("estimated").null();
  }
  j.key("estimate").string(to_string(result.error_estimate));
  j.key("target");
  write_error_target(j, s, result);
  j.end();
  j.key("denoise");
  if (denoised) {
    j.begin_object();
    j.key("estimated_error").number(denoised->estimated_error);
    j.key("noisy_error").number(denoised->noisy_error);
    j.key("seconds").number(denoised->seconds);
    j.end();
  } else {
    j.null();
  }
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
