#pragma once
// `rtiow accuracy`: what each knob buys. Against a cached high-spp reference, measures the
// error and time of the spp sweep with each sampler, the depth limit's bias, Embree against
// the naive loop, Schlick against exact Fresnel, and adaptive sampling; prints tables and
// writes JSON, CSV and a log-log plot.

#include "core/measure/accuracy_options.h"

namespace rtiow {

// Checks the options (every one broken named in one line), then measures.
int run_accuracy_command(const AccuracyOptions& o);

}  // namespace rtiow
