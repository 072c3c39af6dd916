#include "core/render/render_metadata.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "core/limits/input_limits.h"
#include "core/render/render_statistics.h"

namespace rtiow {

Metadata render_metadata(const Scene& scene, const RenderSettings& s, const RenderResult& r,
                         bool reproducible) {
  namespace key = metadata_key;
  Metadata metadata{{key::kScene, scene.name}};
  if (scene.layout_seed) metadata.emplace_back(key::kSceneSeed, std::int64_t(*scene.layout_seed));
  metadata.insert(metadata.end(), {
                                      {key::kDepth, std::int64_t(s.max_depth)},
                                      {key::kSeed, std::int64_t(s.seed)},
                                      {key::kSampler, to_string(s.sampler)},
                                      {key::kAccelerator, to_string(s.accel)},
                                      {key::kRaysTraced, std::int64_t(r.rays_traced)},
                                  });
  if (is_adaptive(s)) {
    // Each pixel has its own count: the range and the mean, not one "spp".
    const auto [least, most] = std::minmax_element(r.pixel_samples.begin(), r.pixel_samples.end());
    if (s.target_error > 0) {
      metadata.emplace_back(key::kTargetError, s.target_error);
      metadata.emplace_back(key::kPixelsAboveTarget, std::int64_t(r.pixels_above_target));
    }
    if (s.image_error > 0) {
      metadata.emplace_back(key::kImageError, s.image_error);
      metadata.emplace_back(key::kEstimatedImageError, r.estimated_image_error);
    }
    if (s.adaptive) {
      metadata.emplace_back(key::kAdaptive, std::string("sqrt(variance/cost)"));
      if (asks_sample_count(s)) {  // else the time limit's
        metadata.emplace_back(key::kSppBudget, std::int64_t(s.samples_per_pixel));
      }
    }
    metadata.insert(
        metadata.end(),
        {
            {key::kSppMin, std::int64_t(*least)},
            {key::kSppMax, std::int64_t(*most)},
            {key::kSppMean, mean_samples(r)},
            {key::kSppLimit, std::int64_t(s.adaptive ? limits::kMostAdaptiveSamples
                                                     : std::uint32_t(s.samples_per_pixel))},
        });
  } else {
    metadata.emplace_back(key::kSpp, std::int64_t(r.samples_completed));
  }
  if (r.stopped) {
    if (!is_adaptive(s))
      metadata.emplace_back(key::kSppRequested, std::int64_t(s.samples_per_pixel));
    metadata.emplace_back(key::kStopped, std::string("interrupted by a signal"));
  } else if (r.time_limited) {
    char limit[64];
    std::snprintf(limit, sizeof limit, "time limit of %g s", s.time_limit_seconds);
    metadata.emplace_back(key::kStopped, std::string(limit));
  }
  if (!reproducible) metadata.emplace_back(key::kRenderSeconds, r.render_seconds);
  return metadata;
}

}  // namespace rtiow
