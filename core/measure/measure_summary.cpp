#include "core/measure/measure_summary.h"
#include "core/limits/setting_name.h"

#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/io/summary_json.h"
#include "core/measure/timing_warnings.h"

namespace rtiow {

std::unique_ptr<OutputClaim> claim_summary(const std::string& path) {
  if (path.empty()) return nullptr;
  check_output_path(path, {}, setting("summary_json").c_str());
  return std::make_unique<OutputClaim>(path);
}
namespace {

using ordered = nlohmann::ordered_json;
using json = nlohmann::json;

// A value of `results` by path, or null where the measurement did not take it.
json at(const json& results, const std::string& path) {
  const json::json_pointer pointer(path);
  return results.contains(pointer) ? results.at(pointer) : json();
}

ordered files_of(const MeasureFiles& files) {
  ordered out;
  out["figures"] = files.figures;
  if (!files.csv.empty()) out["csv"] = files.csv;
  out["plot"] = files.plot.empty() ? ordered() : ordered(files.plot);
  return out;
}

ordered warnings_of(const std::vector<std::string>& candidates) {
  ordered out = ordered::array();
  for (const std::string& warning : candidates) {
    if (!warning.empty()) out.push_back(warning);
  }
  return out;
}

// What every measurement's summary starts with: the shared head and the files it wrote.
ordered measurement_head(const char* command, const MeasureFiles& files) {
  ordered j = summary_head(command, 0);
  j["files"] = files_of(files);
  return j;
}

double rate(const json& results, const char* run) {
  return results["cover"][run]["mrays_per_second"].get<double>();
}

}  // namespace

std::string bench_summary_json(const json& results, const MeasureFiles& files) {
  ordered j = measurement_head("bench", files);
  j["threads"] = results["threads"];
  j["repeat"] = results["repeat"];
  const json& c = results["cover"];
  const double embree = rate(results, "embree"), naive = rate(results, "naive");
  const double one = rate(results, "embree_1_thread");
  j["cover"] = {{"width", c["width"]},
                {"height", c["height"]},
                {"spp", c["spp"]},
                {"depth", c["depth"]},
                {"spheres", c["spheres"]},
                {"rays", c["embree"]["rays"]},
                {"embree_mrays_per_second", embree},
                {"naive_mrays_per_second", naive},
                {"embree_1_thread_mrays_per_second", one},
                {"raw_trace_mrays_per_second", c["trace"]["mrays_per_second"]},
                {"traversal_mrays_per_second", c["traversal"]["mrays_per_second"]},
                {"embree_over_naive", embree / naive},
                {"thread_scaling", embree / one}};
  ordered scaling = ordered::array();
  for (const json& point : results["scaling"]) {
    scaling.push_back({{"spheres", point["n"]},
                       {"embree_mrays_per_second", at(point, "/embree/mrays_per_second")},
                       {"embree_build_seconds", at(point, "/embree/build_seconds")},
                       {"embree_peak_rss_mb", at(point, "/embree/peak_rss_mb")},
                       {"naive_mrays_per_second", at(point, "/naive/mrays_per_second")}});
  }
  j["scaling"] = scaling;
  j["warnings"] = warnings_of({thread_scaling_warning(results["threads"].get<int>(), one, embree)});
  return summary_text(j);
}

std::string accuracy_summary_json(const json& results, const MeasureFiles& files) {
  ordered j = measurement_head("accuracy", files);
  j["scene"] = results["scene"];
  j["width"] = results["width"];
  j["height"] = results["height"];
  j["depth"] = results["depth"];
  j["threads"] = results["threads"];
  j["reference"] = {{"spp", results["reference_spp"]},
                    {"seed", results["reference_seed"]},
                    {"reused", results["reference_reused"]},
                    {"path", results["reference_path"]}};
  const json& summary = results["summary"];
  // The headline: the time each method takes to the book's quality, against the book's own.
  j["book_quality"] = at(summary, "/book_quality");
  j["equal_time_factor"] = at(summary, "/equal_time_factor");
  j["budget_equal_time_factor"] = at(summary, "/budget_equal_time_factor");
  j["rmse_slope"] = at(summary, "/rmse_slope");
  // --image-error: the error asked and the one delivered (against the reference).
  ordered image_error = ordered::array();
  for (const json& row : results["image_error"]) {
    image_error.push_back({{"sampler", row["choice"]},
                           {"asked", row["parameter"]},
                           {"delivered", at(row, "/achieved_error")},
                           {"rmse", row["rmse"]},
                           {"render_seconds", row["seconds"]}});
  }
  j["image_error"] = image_error;
  std::vector<double> depths, times;
  for (const json& row : results["depth_sweep"]) {
    depths.push_back(row["parameter"].get<double>());
    times.push_back(row["seconds"].get<double>());
  }
  j["warnings"] = warnings_of({depth_timing_warning(depths, times)});
  return summary_text(j);
}

}  // namespace rtiow
