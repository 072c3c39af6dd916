#include "core/measure/bench_report.h"
#include "core/limits/setting_name.h"

#include "core/measure/plot_script.h"
#include "core/measure/timing_warnings.h"

#include "core/io/atomic_file.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>

namespace rtiow {
namespace {

namespace fs = std::filesystem;
using json = Figures;

// Sphere tests per nanosecond per core: every naive ray tests every sphere.
double tests_per_ns_per_core(const json& naive) {
  const double tests = naive["rays"].get<double>() * naive["spheres"].get<double>();
  return tests / (naive["render_seconds"].get<double>() * naive["threads"].get<double>() * 1e9);
}

}  // namespace

// "19.50..20.10": a rate's least and most over the runs.
std::string range_of(const json& figures) {
  char text[48];
  std::snprintf(text, sizeof text, "%.2f..%.2f", figures["mrays_per_second_min"].get<double>(),
                figures["mrays_per_second_max"].get<double>());
  return text;
}

// The machine and the build the figures are of (bench.json's "context").
void print_context(const json& context) {
  std::string build;
  for (const json& fact : context["build"]) {
    const std::string text = fact.get<std::string>();
    if (text.rfind("libraries: ", 0) == 0) continue;  // in bench.json; the line stays short
    build += (build.empty() ? "" : "; ") + text;
  }
  std::printf("machine: %s, %u logical cores; rtiow %s; %s\n",
              context["cpu"].get<std::string>().c_str(), context["logical_cores"].get<unsigned>(),
              context["rtiow"].get<std::string>().c_str(), build.c_str());
}

namespace {

// The cover's table: each render's time and rate, the traced rays' rates and their ratios.
void print_cover_table(const json& r) {
  const json& c = r["cover"];
  const double embree = c["embree"]["mrays_per_second"], naive = c["naive"]["mrays_per_second"];
  const double one = c["embree_1_thread"]["mrays_per_second"];
  const double trace = c["trace"]["mrays_per_second"];
  print_context(r["context"]);
  std::printf(
      "Cover scene (%d spheres), %dx%d, %d spp, depth %d, %s sampler, seed %llu, %d "
      "threads\n",
      c["spheres"].get<int>(), c["width"].get<int>(), c["height"].get<int>(), c["spp"].get<int>(),
      c["depth"].get<int>(), c["sampler"].get<std::string>().c_str(),
      c["seed"].get<unsigned long long>(), r["threads"].get<int>());
  std::printf("each measured after a warm-up run: the median of %d runs, and their range\n",
              r["repeat"].get<int>());
  std::printf("  %-28s %9s %9s  %s\n", "", "seconds", "Mrays/s", "range");
  const std::pair<const char*, const char*> renders[] = {
      {"embree", "embree"}, {"naive", "naive"}, {"embree_1_thread", "embree, 1 thread"}};
  for (const auto& [key, label] : renders) {
    std::printf("  %-28s %9.3f %9.2f  %s\n", label, c[key]["render_seconds"].get<double>(),
                c[key]["mrays_per_second"].get<double>(), range_of(c[key]).c_str());
  }
  std::printf("  %-28s %9s %9.2f  %-14s (%.2fM rays the render traced)\n", "raw rtcIntersect1", "",
              trace, range_of(c["trace"]).c_str(), c["trace"]["rays"].get<double>() * 1e-6);
  const double traversal = c["traversal"]["mrays_per_second"];
  std::printf("  %-28s %9s %9.2f  %-14s (the same rays, callback returns at once)\n",
              "embree traversal alone", "", traversal, range_of(c["traversal"]).c_str());
  std::printf("  embree / naive:            %.2fx\n", embree / naive);
  if (c["failed_measurements"].empty()) {
    std::printf("  render / raw trace rate:   %.0f%%\n", 100.0 * embree / trace);
    std::printf("  render / traversal alone:  %.0f%%\n", 100.0 * embree / traversal);
    std::printf("  thread scaling 1 -> %d:     %.2fx\n", r["threads"].get<int>(), embree / one);
  } else {
    for (const json& failed : c["failed_measurements"]) {
      std::printf(
          "  failed measurement: %s (another program was running, or the runs were too "
          "short: %s)\n",
          failed.get<std::string>().c_str(), setting("repeat", "5").c_str());
    }
  }
  if (const std::string warning = thread_scaling_warning(r["threads"].get<int>(), one, embree);
      !warning.empty()) {
    std::fprintf(stderr, "rtiow: %s\n", warning.c_str());  // the table stays the figures
  }
}

// The scaling table: each N's build time, rate and memory with each intersector.
void print_scaling_table(const json& r) {
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
}  // namespace

void print_bench_table(const json& r) {
  print_cover_table(r);
  print_scaling_table(r);
}

void write_bench_json(const json& results, const std::string& path) {
  write_text_atomically(path, figures_text(results, 2) + "\n");
}

void write_bench_csv(const json& results, const std::string& path) {
  std::string csv =
      "section,configuration,spheres,width,height,spp,depth,threads,accelerator,sampler,seed,"
      "run,build_seconds,render_seconds,rays,mrays_per_second\n";
  const auto number = [](const json& figures, const char* key) {
    return figures.contains(key) ? figures_text(figures[key]) : std::string();
  };
  const auto rows = [&](const std::string& section, const std::string& configuration,
                        const json& setup, const json& figures) {
    int run = 0;
    for (const json& each : figures["each_run"]) {
      csv +=
          section + "," + configuration + "," + number(setup, "spheres") + "," +
          number(setup, "width") + "," + number(setup, "height") + "," + number(setup, "spp") +
          "," + number(setup, "depth") + "," + number(figures, "threads") + "," +
          (figures.contains("accelerator") ? figures["accelerator"].get<std::string>() : "embree") +
          "," + (figures.contains("sampler") ? figures["sampler"].get<std::string>() : "") + "," +
          number(figures, "seed") + "," + std::to_string(++run) + "," +
          number(each, "build_seconds") + "," + number(each, "render_seconds") + "," +
          number(figures, "rays") + "," + number(each, "mrays_per_second") + "\n";
    }
  };
  const json& cover = results["cover"];
  for (const char* key : {"embree", "naive", "embree_1_thread", "trace", "traversal"}) {
    rows("cover", key, cover, cover[key]);
  }
  const json& scaling = results["scaling_settings"];
  for (const json& point : results["scaling"]) {
    json setup = scaling;
    setup["spheres"] = point["n"];
    const std::string section = "spheres:" + figures_text(point["n"]);
    for (const char* key : {"embree", "naive"}) {
      if (point.contains(key)) rows(section, key, setup, point[key]);
    }
  }
  write_text_atomically(path, csv);
}

bool plot_bench(const json& results, const std::string& plot_path) {
  return run_plot_script("bench_plot.py", figures_text(results), plot_path);
}

}  // namespace rtiow
