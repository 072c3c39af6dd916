#include "app/measure/bench_command.h"

#include <filesystem>
#include <string>
#include <vector>

#include "app/source_commit.h"
#include "core/measure/bench_compare.h"
#include "core/measure/bench_runs.h"

namespace rtiow {
namespace {

// `rtiow bench-point` with the point's options: this program, run again for one point.
std::vector<std::string> point_command(const PointOptions& p) {
  const std::string exe = std::filesystem::read_symlink("/proc/self/exe").string();
  std::vector<std::string> argv{exe,         "bench-point",
                                "--scene",   p.scene,
                                "--accel",   p.accel,
                                "--width",   std::to_string(p.width),
                                "--height",  std::to_string(p.height),
                                "--spp",     std::to_string(p.spp),
                                "--depth",   std::to_string(p.depth),
                                "--repeat",  std::to_string(p.repeat),
                                "--threads", std::to_string(p.threads),
                                "--budget",  std::to_string(p.budget)};
  if (p.helper) argv.push_back("--helper");
  return argv;
}

}  // namespace

int run_bench_command(BenchOptions o) {
  if (!o.compare.empty()) return compare_bench_files(o.compare[0], o.compare[1]);
  o.commit = source_commit();
  o.point_command = point_command;
  return run_bench(o);
}

int run_bench_point(const PointOptions& o) {
  return run_point(o);  // --helper: main read it first
}

}  // namespace rtiow
