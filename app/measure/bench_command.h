#pragma once
// `rtiow bench`: Embree against the naive loop on the cover scene and on spheres:N from
// 10 to 1M, the raw rtcIntersect1 rate on the rays a render traced, and thread scaling.
// Each scaling point runs in a child process (`rtiow bench-point`, hidden) so its peak
// memory is its own.

#include "core/measure/bench_runs.h"

namespace rtiow {

// rtiow bench: compares two figures files (--compare), or measures (the sources' commit and
// how a point runs in a process of its own filled in here).
int run_bench_command(BenchOptions o);

// rtiow bench-point: one scaling point, in the process bench started.
int run_bench_point(const PointOptions& o);

}  // namespace rtiow
