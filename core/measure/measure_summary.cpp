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

using json = Figures;

// A value of `results` by path, or null where the measurement did not take it.
json at(const json& results, const std::string& path) {
  const json::json_pointer pointer(path);
  return results.contains(pointer) ? results.at(pointer) : json();
}

// `key`: the figure as the measurement took it.
void copy(JsonWriter& j, const char* key, const json& figure) {
  write_figures(j.key(key), figure);
}

void write_files(JsonWriter& j, const MeasureFiles& files) {
  j.key("files").begin_object();
  j.key("figures").string(files.figures);
  if (!files.csv.empty()) j.key("csv").string(files.csv);
  files.plot.empty() ? j.key("plot").null() : j.key("plot").string(files.plot);
  j.end();
}

void write_warnings(JsonWriter& j, const std::vector<std::string>& candidates) {
  j.key("warnings").begin_array();
  for (const std::string& warning : candidates) {
    if (!warning.empty()) j.string(warning);
  }
  j.end();
}

// What every measurement's summary starts with: the shared head and the files it wrote.
JsonWriter measurement_head(const char* command, const MeasureFiles& files) {
  JsonWriter j = begin_summary(command, 0);
  write_files(j, files);
  return j;
}

double rate(const json& results, const char* run) {
  return results["cover"][run]["mrays_per_second"].get<double>();
}

void write_cover(JsonWriter& j, const json& results) {
  const json& c = results["cover"];
  const double embree = rate(results, "embree"), naive = rate(results, "naive");
  const double one = rate(results, "embree_1_thread");
  j.key("cover").begin_object();
  for (const char* key : {"width", "height", "spp", "depth", "spheres"}) copy(j, key, c[key]);
  copy(j, "rays", c["embree"]["rays"]);
  j.key("embree_mrays_per_second").number(embree);
  j.key("naive_mrays_per_second").number(naive);
  j.key("embree_1_thread_mrays_per_second").number(one);
  copy(j, "raw_trace_mrays_per_second", c["trace"]["mrays_per_second"]);
  copy(j, "traversal_mrays_per_second", c["traversal"]["mrays_per_second"]);
  j.key("embree_over_naive").number(embree / naive);
  j.key("thread_scaling").number(embree / one);
  j.end();
}

}  // namespace

std::string bench_summary_json(const json& results, const MeasureFiles& files) {
  JsonWriter j = measurement_head("bench", files);
  copy(j, "threads", results["threads"]);
  copy(j, "repeat", results["repeat"]);
  write_cover(j, results);
  j.key("scaling").begin_array();
  for (const json& point : results["scaling"]) {
    j.begin_object();
    copy(j, "spheres", point["n"]);
    copy(j, "embree_mrays_per_second", at(point, "/embree/mrays_per_second"));
    copy(j, "embree_build_seconds", at(point, "/embree/build_seconds"));
    copy(j, "embree_peak_rss_mb", at(point, "/embree/peak_rss_mb"));
    copy(j, "naive_mrays_per_second", at(point, "/naive/mrays_per_second"));
    j.end();
  }
  j.end();
  const double embree = rate(results, "embree"), one = rate(results, "embree_1_thread");
  write_warnings(j, {thread_scaling_warning(results["threads"].get<int>(), one, embree)});
  return summary_text(j);
}

std::string accuracy_summary_json(const json& results, const MeasureFiles& files) {
  JsonWriter j = measurement_head("accuracy", files);
  for (const char* key : {"scene", "width", "height", "depth", "threads"})
    copy(j, key, results[key]);
  j.key("reference").begin_object();
  copy(j, "spp", results["reference_spp"]);
  copy(j, "seed", results["reference_seed"]);
  copy(j, "reused", results["reference_reused"]);
  copy(j, "path", results["reference_path"]);
  j.end();
  const json& summary = results["summary"];
  // The headline: the time each method takes to the book's quality, against the book's own.
  for (const char* key :
       {"book_quality", "equal_time_factor", "budget_equal_time_factor", "rmse_slope"})
    copy(j, key, at(summary, std::string("/") + key));
  // --image-error: the error asked and the one delivered (against the reference).
  j.key("image_error").begin_array();
  for (const json& row : results["image_error"]) {
    j.begin_object();
    copy(j, "sampler", row["choice"]);
    copy(j, "asked", row["parameter"]);
    copy(j, "delivered", at(row, "/achieved_error"));
    copy(j, "rmse", row["rmse"]);
    copy(j, "render_seconds", row["seconds"]);
    j.end();
  }
  j.end();
  std::vector<double> depths, times;
  for (const json& row : results["depth_sweep"]) {
    depths.push_back(row["parameter"].get<double>());
    times.push_back(row["seconds"].get<double>());
  }
  write_warnings(j, {depth_timing_warning(depths, times)});
  return summary_text(j);
}

}  // namespace rtiow
