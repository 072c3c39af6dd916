#include "app/measure/bench_report.h"

#include "app/measure/plot_script.h"
#include "app/measure/timing_warnings.h"

#include "core/io/atomic_file.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace rtiow {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Sphere tests per nanosecond per core: every naive ray tests every sphere.
double tests_per_ns_per_core(const json& naive) {
  const double tests = naive["rays"].get<double>() * naive["spheres"].get<double>();
  return tests / (naive["render_seconds"].get<double>() * naive["threads"].get<double>() * 1e9);
}

}  // namespace

void print_bench_table(const json& r) {
  const json& c = r["cover"];
  const double embree = c["embree"]["mrays_per_second"], naive = c["naive"]["mrays_per_second"];
  const double one = c["embree_1_thread"]["mrays_per_second"];
  const double trace = c["trace"]["mrays_per_second"];
  std::printf("Cover scene (%d spheres), %dx%d, %d spp, depth %d, %d threads, median of %d\n",
              c["spheres"].get<int>(), c["width"].get<int>(), c["height"].get<int>(),
              c["spp"].get<int>(), c["depth"].get<int>(), r["threads"].get<int>(),
              r["repeat"].get<int>());
  std::printf("  %-28s %9s %9s\n", "", "seconds", "Mrays/s");
  std::printf("  %-28s %9.3f %9.2f\n", "embree", c["embree"]["render_seconds"].get<double>(),
              embree);
  std::printf("  %-28s %9.3f %9.2f\n", "naive", c["naive"]["render_seconds"].get<double>(), naive);
  std::printf("  %-28s %9.3f %9.2f\n", "embree, 1 thread",
              c["embree_1_thread"]["render_seconds"].get<double>(), one);
  std::printf("  %-28s %9s %9.2f   (%.2fM rays the render traced)\n", "raw rtcIntersect1", "",
              trace, c["trace"]["rays"].get<double>() * 1e-6);
  const double traversal = c["traversal"]["mrays_per_second"];
  std::printf("  %-28s %9s %9.2f   (the same rays, callback returns at once)\n",
              "embree traversal alone", "", traversal);
  std::printf("  embree / naive:            %.2fx\n", embree / naive);
  std::printf("  render / raw trace rate:   %.0f%%\n", 100.0 * embree / trace);
  std::printf("  render / traversal alone:  %.0f%%\n", 100.0 * embree / traversal);
  std::printf("  thread scaling 1 -> %d:     %.2fx\n", r["threads"].get<int>(), embree / one);
  if (const std::string warning = thread_scaling_warning(r["threads"].get<int>(), one, embree);
      !warning.empty()) {
    std::fprintf(stderr, "rtiow: %s\n", warning.c_str());  // the table stays the figures
  }

  const json& s = r["scaling_settings"];
  std::printf("\nScaling, spheres:N (N small spheres + ground + 3 big), %dx%d, %d spp, depth %d\n",
              s["width"].get<int>(), s["height"].get<int>(), s["spp"].get<int>(),
              s["depth"].get<int>());
  std::printf("  %9s | %8s %9s %8s | %9s %8s %12s | %8s\n", "N", "build s", "Mrays/s", "peak MB",
              "Mrays/s", "peak MB", "tests/ns/core", "emb/naive");
  std::printf("  %9s | %-27s | %-34s |\n", "", "embree", "naive");
  for (const json& p : r["scaling"]) {
    const json& e = p["embree"];
    std::printf("  %9llu | %8.3f %9.2f %8.0f |", p["n"].get<unsigned long long>(),
                e["build_seconds"].get<double>(), e["mrays_per_second"].get<double>(),
                e["peak_rss_mb"].get<double>());
    if (p.contains("naive")) {
      const json& n = p["naive"];
      std::printf(" %9.3f %8.0f %12.2f | %8.1f\n", n["mrays_per_second"].get<double>(),
                  n["peak_rss_mb"].get<double>(), tests_per_ns_per_core(n),
                  e["mrays_per_second"].get<double>() / n["mrays_per_second"].get<double>());
    } else {
      std::printf(" %-34s |\n", " skipped (over the time budget)");
    }
  }
  if (!r["scaling"].empty()) {
    std::printf(
        "  peak MB is the process's peak resident memory; %.0f MB of it is there at start-up "
        "(shared libraries)\n",
        r["scaling"][0]["embree"]["startup_rss_mb"].get<double>());
  }
  for (const json& p : r["scaling"]) {
    if (p.contains("naive_skipped")) {
      std::printf("  naive stopped at N = %llu: %s\n", p["n"].get<unsigned long long>(),
                  p["naive_skipped"].get<std::string>().c_str());
      break;
    }
  }
}

void write_bench_json(const json& results, const std::string& path) {
  write_text_atomically(path, results.dump(2) + "\n");
}

bool plot_bench(const json& results, const std::string& plot_path) {
  return run_plot_script("bench_plot.py", results.dump(), plot_path);
}

}  // namespace rtiow
