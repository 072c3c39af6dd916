#include "core/measure/bench_compare.h"
#include "core/limits/setting_name.h"

#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/io/input_file.h"
#include "core/limits/error.h"

namespace rtiow {
namespace {

using json = nlohmann::json;

constexpr std::uint64_t kMostBenchBytes = std::uint64_t(16) << 20;

json read_bench(const std::string& path) {
  const InputFile file(path, kMostBenchBytes, "bench figures");
  json figures = json::parse(file.first_bytes(std::size_t(file.size())), nullptr, false);
  if (figures.is_discarded() || !figures.is_object() || !figures.contains("cover") ||
      !figures["cover"].is_object()) {
    throw InvalidInput("bench figures " + quote_value(path) + ": not a bench.json (rtiow bench " +
                       setting("out", "DIR") + " writes one)");
  }
  return figures;
}

// A rate: its median, and its least and most where the file kept them (else the median).
struct Rate {
  double median = 0, least = 0, most = 0;
  bool spread = false;
};

std::optional<Rate> rate_of(const json& figures) {
  if (!figures.is_object() || !figures.contains("mrays_per_second") ||
      !figures["mrays_per_second"].is_number()) {
    return std::nullopt;
  }
  Rate r;
  r.median = r.least = r.most = figures["mrays_per_second"].get<double>();
  // One run has no spread to judge a difference by.
  const bool runs =
      figures.contains("runs") && figures["runs"].is_number() && figures["runs"].get<double>() >= 2;
  if (runs && figures.contains("mrays_per_second_min") &&
      figures.contains("mrays_per_second_max") && figures["mrays_per_second_min"].is_number() &&
      figures["mrays_per_second_max"].is_number()) {
    r.least = figures["mrays_per_second_min"].get<double>();
    r.most = figures["mrays_per_second_max"].get<double>();
    r.spread = true;
  }
  return r;
}

std::string machine_of(const json& figures) {
  if (!figures.contains("context") || !figures["context"].is_object()) {
    return "no context recorded";
  }
  const json& c = figures["context"];
  const auto text = [&](const char* key) {
    return c.contains(key) && c[key].is_string() ? c[key].get<std::string>() : std::string("?");
  };
  return text("cpu") + ", rtiow " + text("rtiow");
}

void compare_row(const std::string& label, const json& a, const json& b, int& beyond) {
  const std::optional<Rate> ra = rate_of(a), rb = rate_of(b);
  if (!ra || !rb) return;
  std::string verdict;
  if (!ra->spread || !rb->spread) {
    verdict = "no ranges to judge by";
  } else if (rb->least > ra->most || rb->most < ra->least) {
    verdict = rb->median > ra->median ? "faster, beyond the noise" : "slower, beyond the noise";
    ++beyond;
  } else {
    verdict = "within the noise";
  }
  std::printf("  %-28s %9.2f %9.2f %7.3fx  %s\n", label.c_str(), ra->median, rb->median,
              rb->median / ra->median, verdict.c_str());
}

}  // namespace

int compare_bench_files(const std::string& before, const std::string& after) {
  const json a = read_bench(before), b = read_bench(after);
  std::printf("A: %s (%s)\nB: %s (%s)\n", one_line(before).c_str(), machine_of(a).c_str(),
              one_line(after).c_str(), machine_of(b).c_str());
  std::printf("  %-28s %9s %9s %8s  %s\n", "Mrays/s (medians)", "A", "B", "B/A",
              "beyond the noise where the runs' ranges do not overlap");
  int beyond = 0;
  const std::vector<std::pair<const char*, const char*>> cover = {
      {"embree", "cover, embree"},
      {"naive", "cover, naive"},
      {"embree_1_thread", "cover, embree, 1 thread"},
      {"trace", "cover, raw rtcIntersect1"},
      {"traversal", "cover, traversal alone"}};
  for (const auto& [key, label] : cover) {
    if (a["cover"].contains(key) && b["cover"].contains(key)) {
      compare_row(label, a["cover"][key], b["cover"][key], beyond);
    }
  }
  if (a.contains("scaling") && b.contains("scaling") && a["scaling"].is_array() &&
      b["scaling"].is_array()) {
    for (const json& pa : a["scaling"]) {
      for (const json& pb : b["scaling"]) {
        if (!pa.contains("n") || !pb.contains("n") || pa["n"] != pb["n"]) continue;
        for (const char* accel : {"embree", "naive"}) {
          if (pa.contains(accel) && pb.contains(accel)) {
            compare_row("spheres:" + pa["n"].dump() + ", " + accel, pa[accel], pb[accel], beyond);
          }
        }
      }
    }
  }
  std::printf("%d figure%s differ beyond the noise\n", beyond, beyond == 1 ? "" : "s");
  return 0;
}

}  // namespace rtiow
