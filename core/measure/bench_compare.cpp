#include "core/measure/bench_compare.h"
#include "core/limits/setting_name.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/io/input_file.h"
#include "core/limits/error.h"
#include "core/limits/number_text.h"
#include "core/scene_file/json_stream.h"

namespace rtiow {
namespace {

constexpr std::uint64_t kMostBenchBytes = std::uint64_t(16) << 20;

// A number member of `object`, if it has one.
std::optional<double> number_of(const JsonValue& object, const char* key) {
  const JsonValue* value = find_member(object, key);
  if (!value || !value->IsNumber()) return std::nullopt;
  return value->GetDouble();
}

// An object member of `object`, or null.
const JsonValue* object_of(const JsonValue& object, const char* key) {
  const JsonValue* value = find_member(object, key);
  return value && value->IsObject() ? value : nullptr;
}

// A sphere count as bench.json wrote it ("100000", not "1e+05").
std::string count_text(double n) {
  return n == std::floor(n) && std::fabs(n) < 9e15 ? std::to_string(std::int64_t(n))
                                                   : shortest_text(n);
}

// Read by the reader every JSON input goes through: bounded, no duplicate keys.
void read_bench(const std::string& path, JsonDocument& figures) {
  const InputFile file(path, kMostBenchBytes, "bench figures");
  const std::string text = file.first_bytes(std::size_t(file.size()));
  const std::string source = "bench figures " + quote_value(path);
  try {
    JsonInput input(JsonInput::from_text(text), text.size(), source);
    parse_json_stream(input, source, {}, figures);
  } catch (const InvalidInput&) {
    figures.SetNull();
  }
  if (!object_of(figures, "cover")) {
    throw InvalidInput(source + ": not a bench.json (rtiow bench " + setting("out", "DIR") +
                       " writes one)");
  }
}

// A rate: its median, and its least and most where the file kept them (else the median).
struct Rate {
  double median = 0, least = 0, most = 0;
  bool spread = false;
};

std::optional<Rate> rate_of(const JsonValue& figures) {
  const std::optional<double> median = number_of(figures, "mrays_per_second");
  if (!median) return std::nullopt;
  Rate r;
  r.median = r.least = r.most = *median;
  // One run has no spread to judge a difference by.
  const std::optional<double> runs = number_of(figures, "runs");
  const std::optional<double> least = number_of(figures, "mrays_per_second_min");
  const std::optional<double> most = number_of(figures, "mrays_per_second_max");
  if (runs && *runs >= 2 && least && most) {
    r.least = *least, r.most = *most;
    r.spread = true;
  }
  return r;
}

std::string machine_of(const JsonValue& figures) {
  const JsonValue* c = object_of(figures, "context");
  if (!c) return "no context recorded";
  const auto text = [&](const char* key) {
    const JsonValue* value = find_member(*c, key);
    return value && value->IsString() ? std::string(text_of(*value)) : std::string("?");
  };
  return text("cpu") + ", rtiow " + text("rtiow");
}

void compare_row(const std::string& label, const JsonValue& a, const JsonValue& b, int& beyond) {
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
  JsonDocument a, b;
  read_bench(before, a), read_bench(after, b);
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
    const JsonValue* in_a = find_member(*object_of(a, "cover"), key);
    const JsonValue* in_b = find_member(*object_of(b, "cover"), key);
    if (in_a && in_b) compare_row(label, *in_a, *in_b, beyond);
  }
  const JsonValue* scaling_a = find_member(a, "scaling");
  const JsonValue* scaling_b = find_member(b, "scaling");
  if (scaling_a && scaling_b && scaling_a->IsArray() && scaling_b->IsArray()) {
    for (const JsonValue& pa : scaling_a->GetArray()) {
      for (const JsonValue& pb : scaling_b->GetArray()) {
        const std::optional<double> na = number_of(pa, "n"), nb = number_of(pb, "n");
        if (!na || !nb || *na != *nb) continue;
        for (const char* accel : {"embree", "naive"}) {
          const JsonValue* ra = find_member(pa, accel);
          const JsonValue* rb = find_member(pb, accel);
          if (ra && rb) compare_row("spheres:" + count_text(*na) + ", " + accel, *ra, *rb, beyond);
        }
      }
    }
  }
  std::printf("%d figure%s differ beyond the noise\n", beyond, beyond == 1 ? "" : "s");
  return 0;
}

}  // namespace rtiow
