#pragma once
// `rtiow accuracy`: what each knob buys. Against a cached high-spp reference, measures the
// error and time of the spp sweep with each sampler, the depth limit's bias, Embree against
// the naive loop, Schlick against exact Fresnel, and adaptive sampling; prints tables and
// writes JSON, CSV and a log-log plot.

#include <CLI/CLI.hpp>

#include <functional>

namespace rtiow {

std::function<int()> add_accuracy_command(CLI::App& app);

}  // namespace rtiow
