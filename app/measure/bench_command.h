#pragma once
// `rtiow bench`: Embree against the naive loop on the cover scene and on spheres:N from
// 10 to 1M, the raw rtcIntersect1 rate on the rays a render traced, and thread scaling.
// Each scaling point runs in a child process (`rtiow bench-point`, hidden) so its peak
// memory is its own.

#include <CLI/CLI.hpp>

#include <functional>

namespace rtiow {

std::function<int()> add_bench_command(CLI::App& app);

}  // namespace rtiow
