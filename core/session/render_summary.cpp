#include "core/session/render_summary.h"

#include <nlohmann/json.hpp>

#include "core/io/summary_json.h"
#include "core/parallel/thread_count.h"
#include "core/render/render_outcome.h"
#include "core/render/render_statistics.h"
#include "core/sampling/sampler.h"

namespace rtiow {

std::string render_summary_json(const RenderJob& job, const RenderResult& result, int ranks,
                                int exit_code, bool image_written,
                                const std::optional<DenoiseFigures>& denoised) {
  using json = nlohmann::ordered_json;
  const RenderSettings& s = job.settings;
  const RenderOutcome outcome = describe_outcome(s, result);
  const double seconds = result.render_seconds;
  json j = summary_head("render", exit_code);
  j["output"] = image_written ? json(job.output) : json();
  j["scene"] = job.scene.name;
  j["width"] = s.width;
  j["height"] = s.height;
  j["crop"] = s.crop ? json{s.crop->x0, s.crop->y0, s.crop->x1, s.crop->y1} : json();
  json passes = json::array();
  if (s.passes.albedo) passes.push_back("albedo");
  if (s.passes.normal) passes.push_back("normal");
  if (s.passes.depth) passes.push_back("depth");
  j["passes"] = passes;
  j["depth"] = s.max_depth;
  j["accelerator"] = to_string(s.accel);
  j["sampler"] = to_string(s.sampler);
  j["seed"] = s.seed;
  j["threads"] = thread_count(s.threads);
  j["ranks"] = ranks;
  const std::optional<int> asked = spp_option(s.samples);
  j["spp"] = {{"least", outcome.least},
              {"most", outcome.most},
              {"mean", outcome.mean},
              {"asked", asked ? json(*asked) : json()}};
  j["samples"] = outcome.samples;
  j["stopped"] = outcome.stopped.empty() ? json() : json(outcome.stopped);
  j["render_seconds"] = seconds;
  j["build_seconds"] = result.build_seconds;
  j["rays"] = result.rays_traced;
  j["mrays_per_second"] = seconds > 0 ? double(result.rays_traced) / seconds * 1e-6 : 0.0;
  // Every render's estimate of its image error, and the error-driven modes' goal.
  const bool estimated = result.error_estimate != ErrorEstimate::None;
  json target;
  if (const auto* image = std::get_if<ImageErrorTarget>(&s.samples)) {
    target = {{"kind", image->denoised ? "denoised image" : "image"},
              {"asked", image->error},
              {"reached", error_target_reached(s, result)}};
  } else if (const auto* pixel = std::get_if<PixelErrorTarget>(&s.samples)) {
    target = {{"kind", "pixel"},
              {"asked", pixel->error},
              {"pixels_above", result.pixels_above_target},
              {"reached", error_target_reached(s, result)}};
  }
  j["error"] = {{"estimated", estimated ? json(result.estimated_image_error) : json()},
                {"estimate", to_string(result.error_estimate)},
                {"target", target}};
  j["denoise"] = denoised ? json{{"estimated_error", denoised->estimated_error},
                                 {"noisy_error", denoised->noisy_error},
                                 {"seconds", denoised->seconds}}
                          : json();
  return summary_text(j);
}

}  // namespace rtiow
