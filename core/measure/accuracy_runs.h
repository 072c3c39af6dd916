#pragma once
// `rtiow accuracy`'s measured renders: each sweep of one knob, rendered `repeat` times and
// measured against the reference.

#include "core/film/image_error.h"
#include "core/measure/accuracy_options.h"
#include "core/measure/figures.h"
#include "core/render/render_request.h"
#include "core/scene/scene.h"

namespace rtiow {

// Every sweep's rows, by group ("spp", "budget", "image_error", "depth_sweep", "intersector",
// "fresnel", "adaptive"), added to `figures`. `base` is the request every render starts from.
void run_sweeps(const AccuracyOptions& o, const Scene& scene, const RenderRequest& base,
                const ImageEstimate& reference, Figures& figures);

}  // namespace rtiow
