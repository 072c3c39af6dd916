#include "core/measure/accuracy_fits.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace rtiow {

using json = Figures;

std::pair<double, double> log_log_fit(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  return {slope, (sy - slope * sx) / n};
}

std::vector<double> column(const json& rows, const std::string& key) {
  std::vector<double> values;
  for (const json& r : rows) values.push_back(r[key].get<double>());
  return values;
}

std::pair<double, double> error_cost_fit(const json& rows, const char* cost, double min_spp) {
  std::vector<double> c, e;
  for (const json& r : rows) {
    if (r["parameter"].get<double>() >= min_spp) {
      c.push_back(r[cost].get<double>());
      e.push_back(r["rel_mse"].get<double>());
    }
  }
  return log_log_fit(c, e);
}

std::pair<double, double> error_time_fit(const json& rows, double min_spp) {
  return error_cost_fit(rows, "seconds", min_spp);
}

// How much lower a method's relMSE is than a baseline's (independent sampling's, or uniform
// sampling's with the same sampler) at the same time, from the baseline's log-log fit.
json equal_time_factors(const json& baseline, const json& rows) {
  const auto [slope, intercept] = error_time_fit(baseline);
  json factors = json::array();
  for (const json& r : rows) {
    const double seconds = r["seconds"].get<double>();
    const double expected = std::exp(intercept + slope * std::log(seconds));
    factors.push_back({{"parameter", r["parameter"]},
                       {"seconds", seconds},
                       {"factor", expected / r["rel_mse"].get<double>()}});
  }
  return factors;
}

double median_factor(const json& factors, double min_parameter) {
  std::vector<double> f;
  for (const json& r : factors) {
    if (r["parameter"].get<double>() >= min_parameter) f.push_back(r["factor"].get<double>());
  }
  if (f.empty()) return 0.0;
  std::sort(f.begin(), f.end());
  return f[f.size() / 2];
}

namespace {

// The seconds (or rays) a sweep needs to reach `rel_mse`, from its fit (spp >= 16: the
// regime of the goal, where every sampler's slope has settled).
double cost_to_reach(const json& rows, const char* cost, double rel_mse) {
  const auto [slope, intercept] = error_cost_fit(rows, cost, 16);
  return std::exp((std::log(rel_mse) - intercept) / slope);
}

// The headline: the relMSE the book's estimator reaches at the book's spp (from the fit of
// relMSE against spp), and how long each method takes to reach it.
json book_quality(const json& r, int book_spp) {
  const json& book = r["book"];
  std::vector<double> spp, e;
  for (const json& row : book) {
    if (row["parameter"].get<double>() >= 16) {
      spp.push_back(row["parameter"].get<double>());
      e.push_back(row["rel_mse"].get<double>());
    }
  }
  const auto [slope, intercept] = log_log_fit(spp, e);
  const double goal = std::exp(intercept + slope * std::log(double(book_spp)));
  const double baseline = cost_to_reach(book, "seconds", goal);
  const double baseline_rays = cost_to_reach(book, "rays", goal);
  json q = {{"book_spp", book_spp}, {"rel_mse", goal}, {"book_seconds", baseline}};
  json methods = json::array();
  for (const auto& [group, label] :
       {std::pair<const char*, const char*>{"spp", "uniform"}, {"budget", "adaptive"}}) {
    for (const SamplerKind kind : kAccuracySamplers) {
      const std::string name = to_string(kind);
      if (!r[group].contains(name)) continue;
      const double seconds = cost_to_reach(r[group][name], "seconds", goal);
      methods.push_back(
          {{"sampler", name},
           {"mode", label},
           {"seconds", seconds},
           {"speedup", baseline / seconds},
           {"ray_factor", baseline_rays / cost_to_reach(r[group][name], "rays", goal)}});
    }
  }
  q["methods"] = methods;
  return q;
}

}  // namespace

json summarise(const json& r, const AccuracyOptions& o) {
  json s;
  const json& independent = r["spp"]["independent"];
  for (const SamplerKind kind : kAccuracySamplers) {
    const std::string name = to_string(kind);
    const json& rows = r["spp"][name];
    s["rmse_slope"][name] = log_log_fit(column(rows, "parameter"), column(rows, "rmse")).first;
    if (kind == SamplerKind::Independent) continue;
    json equal_spp = json::array();
    for (std::size_t i = 0; i < rows.size(); ++i) {
      equal_spp.push_back(
          {{"parameter", rows[i]["parameter"]},
           {"factor", independent[i]["rel_mse"].get<double>() / rows[i]["rel_mse"].get<double>()}});
    }
    s["equal_spp_factors"][name] = equal_spp;
    s["equal_spp_factor"][name] = median_factor(equal_spp, 16);
    s["equal_time_factors"][name] = equal_time_factors(independent, rows);
    s["equal_time_factor"][name] = median_factor(s["equal_time_factors"][name], 16);
  }
  for (const SamplerKind kind : kAccuracySamplers) {
    const std::string name = to_string(kind);
    s["budget_equal_time_factors"][name] = equal_time_factors(r["spp"][name], r["budget"][name]);
    s["budget_equal_time_factor"][name] = median_factor(s["budget_equal_time_factors"][name], 32);
  }
  s["adaptive_equal_time_factors"] = equal_time_factors(independent, r["adaptive"]);
  s["image_error_equal_time_factors"] =
      equal_time_factors(r["spp"][r["image_error_sampler"].get<std::string>()], r["image_error"]);
  const json& denoised_baseline = r["spp"][r["denoised_sampler"].get<std::string>()];
  s["denoised_equal_time_factors"] = equal_time_factors(denoised_baseline, r["denoised"]);
  s["denoised_equal_time_factor"] = median_factor(s["denoised_equal_time_factors"], 16);
  s["book_quality"] = book_quality(r, o.book_spp);
  return s;
}

}  // namespace rtiow
