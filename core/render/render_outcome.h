#pragma once
// How a render ended, described once for every place that reports it: the file's metadata
// (core/render/render_metadata.cpp), the command's summary line and its interrupt line.

#include <cstdint>
#include <string>

#include "core/render/render_settings.h"

namespace rtiow {

struct RenderOutcome {
  // Each pixel's sample count: one count for a uniform render, a range for an adaptive one.
  std::uint32_t least = 0, most = 0;
  double mean = 0.0;
  // "64 spp", or "16-920 spp (mean 46.1, target error 0.05)" with the goal and whether it was
  // reached.
  std::string samples;
  // The image's estimated error: "image error 0.0123 estimated", "image error at most 0.0456"
  // (one Sobol sequence), or empty where there is none or the goal above already says it.
  std::string error;
  // What was asked, where a signal stopped the render: " (of 100 asked)", " (of a budget of 64
  // spp)", " (of a cap of 1024 spp)"; empty with only a time limit.
  std::string asked;
  // Why the render ended early: the stop's cause ("interrupted by a signal", as the command
  // line says; "stopped on request" unless the caller said why) or "time limit of 10 s"; empty
  // when it did all it was asked.
  std::string stopped;
};

RenderOutcome describe_outcome(const RenderSettings& settings, const RenderResult& result);

// Whether an error-driven render reached its target (--image-error: the estimate at or below
// it; --target-error: no pixel above it); true for the other modes, which have none.
bool error_target_reached(const RenderSettings& settings, const RenderResult& result);

}  // namespace rtiow
