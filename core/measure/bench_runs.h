#pragma once
// rtiow bench as the library runs it: Embree against the naive loop on the cover, scaling to a
// million spheres (each point in a process of its own, `rtiow bench-point`), the raw
// rtcIntersect1 rate and thread scaling; a table on stdout, bench.json, bench.csv and bench.png.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/render/render_settings.h"
#include "core/sampling/sampler.h"

namespace rtiow {

struct PointOptions {
  std::string scene;
  std::string accel = "embree";
  int width = 400, height = 225, spp = 2, depth = 8, repeat = 3, threads = 0;
  double budget = 60.0;
  std::string roulette = roulette_name(true);  // off: the book's (and the lean tracer's) paths
  std::string sampler = to_string(SamplerKind::Independent);  // the book's; sobol: render's
  bool helper = false;  // started by bench, which says what a signal did
};

struct BenchOptions {
  int width = 400, height = 225, spp = 8, depth = 20;
  int scaling_width = 400, scaling_height = 225, scaling_spp = 4, scaling_depth = 8;
  std::uint64_t max_spheres = 1'000'000;
  double naive_budget = 60.0;
  int repeat = 3;
  int threads = 0;
  std::string out_dir = "bench";  // bench.json and bench.png
  std::string summary_json;       // empty: none
  bool quick = false;
  std::vector<std::string> compare;  // two bench.json files to compare instead of measuring
  std::string commit;                // the sources' commit, as the program was built from them
  // The program and arguments that run one scaling point in a process of its own (the front
  // end's spelling of `rtiow bench-point`), which prints the point's figures as one JSON line.
  std::function<std::vector<std::string>(const PointOptions&)> point_command;
};

// Measures and reports; the exit status (0, or 1 where a measurement failed).
int run_bench(const BenchOptions& o);

// One scaling point, run in the process `rtiow bench-point` starts: its figures as one JSON
// line on stdout; the exit status.
int run_point(const PointOptions& o);

}  // namespace rtiow
