#include "app/accuracy_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/accuracy_reference.h"
#include "app/cli_checks.h"
#include "app/plot_script.h"
#include "app/quick_run.h"
#include "core/film/image_error.h"
#include "core/io/atomic_file.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/render/render.h"
#include "core/render/render_statistics.h"
#include "core/scene/builtin_scenes.h"

namespace rtiow {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// The seed of the reference: far from the seeds users pick, so the measured renders are
// independent of it.
constexpr std::uint64_t kReferenceSeed = 0x5eed0000acc0ull;

struct AccuracyOptions {
  std::string scene = "cover";
  std::uint64_t scene_seed = 1;
  int width = 160;
  int reference_spp = 8192;
  int max_spp = 1024;
  int fixed_spp = 64;
  std::uint64_t seed = 1;
  int threads = 0;
  int repeat = 3;
  std::vector<int> depths{1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 50};
  std::vector<double> target_errors{0.2, 0.1, 0.07, 0.05, 0.035};
  std::vector<double> image_errors{0.1, 0.05, 0.03, 0.02};
  int book_spp = 500;  // the book's choice: its quality is the headline's goal
  std::string out_dir = "accuracy";
  std::string cache_dir;  // default: $XDG_CACHE_HOME/rtiow or ~/.cache/rtiow
  bool quiet = false;
  bool quick = false;
};

std::string default_cache_dir() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    return (fs::path(xdg) / "rtiow").string();
  }
  if (const char* home = std::getenv("HOME"); home && *home) {
    return (fs::path(home) / ".cache" / "rtiow").string();
  }
  return ".rtiow-cache";
}

// One measured render: its image error against the reference and its median time.
struct Trial {
  json row;
  RenderResult result;
};

class Experiment {
 public:
  Experiment(const AccuracyOptions& o, const Scene& scene, const RenderSettings& base,
             const ImageEstimate& reference)
      : o_(o), scene_(scene), base_(base), reference_(reference) {}

  // Renders `repeat` times (the image is the same each time; only the time varies) and
  // measures the first against the reference.
  Trial run(const std::string& group, const std::string& choice, double parameter,
            const RenderSettings& settings, const Scene* scene = nullptr) const {
    const Scene& s = scene ? *scene : scene_;
    std::vector<double> seconds;
    Trial trial;
    for (int i = 0; i < o_.repeat; ++i) {
      RenderResult r = render(s, settings);
      seconds.push_back(r.render_seconds);
      if (i == 0) trial.result = std::move(r);
    }
    std::sort(seconds.begin(), seconds.end());
    const double median = seconds[seconds.size() / 2];
    const ImageError e = measure_error(to_estimate(trial.result), reference_);
    trial.row = {{"group", group},
                 {"choice", choice},
                 {"parameter", parameter},
                 {"spp_mean", mean_samples(trial.result)},
                 {"depth", settings.max_depth},
                 {"seconds", median},
                 {"rays", trial.result.rays_traced},
                 {"rmse", e.rmse},
                 {"rel_mse", e.rel_mse},
                 {"efficiency", e.rel_mse > 0 ? 1.0 / (e.rel_mse * median) : 0.0},
                 {"mean_difference", e.mean_difference},
                 {"mean_difference_error", e.mean_difference_error},
                 {"rms_bias", e.rms_bias},
                 {"rms_noise", e.rms_noise}};
    if (!o_.quiet) {
      std::fprintf(stderr, "accuracy: %-10s %-12s %8g: %7.3f s, relMSE %.3g\n", group.c_str(),
                   choice.c_str(), parameter, median, e.rel_mse);
    }
    return trial;
  }

  RenderSettings settings() const { return base_; }

 private:
  const AccuracyOptions& o_;
  const Scene& scene_;
  const RenderSettings base_;
  const ImageEstimate& reference_;
};

// Least-squares slope and intercept of log(y) against log(x).
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

constexpr SamplerKind kSamplers[] = {SamplerKind::Independent, SamplerKind::Sobol,
                                     SamplerKind::PaddedSobol};

// Uniform sampling at spp 1, 2, 4, ... max_spp; or --adaptive on the budget of 32..max_spp
// uniform samples (16 is the minimum every pixel takes).
json sweep_spp(const Experiment& x, const AccuracyOptions& o, SamplerKind sampler,
               bool adaptive = false) {
  json rows = json::array();
  for (int spp = adaptive ? 32 : 1; spp <= o.max_spp; spp *= 2) {
    RenderSettings s = x.settings();
    s.samples = adaptive ? SampleBudget(AdaptiveBudget{spp}) : SampleBudget(FixedSamples{spp});
    s.sampler = sampler;
    rows.push_back(x.run(adaptive ? "budget" : "spp", to_string(sampler), spp, s).row);
  }
  return rows;
}

json sweep_image_error(const Experiment& x, const AccuracyOptions& o, SamplerKind sampler) {
  json rows = json::array();
  for (const double target : o.image_errors) {
    RenderSettings s = x.settings();
    s.samples = ImageErrorTarget{target, 4 * o.max_spp};
    s.sampler = sampler;
    Trial t = x.run("image_error", to_string(sampler), target, s);
    t.row["achieved_error"] = std::sqrt(t.row["rel_mse"].get<double>());
    rows.push_back(t.row);
  }
  return rows;
}

json sweep_depth(const Experiment& x, const AccuracyOptions& o) {
  json rows = json::array();
  for (const int depth : o.depths) {
    RenderSettings s = x.settings();
    s.samples = FixedSamples{o.fixed_spp};
    s.max_depth = depth;
    rows.push_back(x.run("depth", "independent", depth, s).row);
  }
  return rows;
}

// Embree against the naive loop: the same sphere test, so the same image is expected.
json compare_intersectors(const Experiment& x, const AccuracyOptions& o) {
  json rows = json::array();
  RenderSettings s = x.settings();
  s.samples = FixedSamples{o.fixed_spp};
  const Trial embree = x.run("intersector", "embree", o.fixed_spp, s);
  s.accel = AccelKind::Naive;
  Trial naive = x.run("intersector", "naive", o.fixed_spp, s);
  naive.row["identical_to_embree"] = naive.result.film.pixels() == embree.result.film.pixels();
  rows.push_back(embree.row);
  rows.push_back(naive.row);
  return rows;
}

// The reference uses the scene's Fresnel model (Schlick for the book's scenes); an exact
// render at more samples shows the bias between the two.
json compare_fresnel(const Experiment& x, const AccuracyOptions& o, const Scene& scene) {
  json rows = json::array();
  RenderSettings s = x.settings();
  s.samples = FixedSamples{4 * o.fixed_spp};
  for (const FresnelModel model : {FresnelModel::Schlick, FresnelModel::Exact}) {
    Scene variant = scene;
    for (Material& m : variant.materials) {
      if (auto* d = std::get_if<Dielectric>(&m)) d->fresnel = model;
    }
    const std::string name(to_string(model));
    rows.push_back(x.run("fresnel", name, 4 * o.fixed_spp, s, &variant).row);
  }
  return rows;
}

json sweep_adaptive(const Experiment& x, const AccuracyOptions& o) {
  json rows = json::array();
  for (const double target : o.target_errors) {
    RenderSettings s = x.settings();
    s.samples = PixelErrorTarget{target, 4 * o.max_spp};
    Trial t = x.run("adaptive", "independent", target, s);
    t.row["achieved_error"] = std::sqrt(t.row["rel_mse"].get<double>());
    rows.push_back(t.row);
  }
  return rows;
}

// The log-log fit of relMSE against a cost ("seconds", or "rays", which unlike seconds is a
// pure function of the settings) over a sweep's rows with spp >= min_spp (below 4 the times
// are too short to trust).
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

std::pair<double, double> error_time_fit(const json& rows, double min_spp = 4) {
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

void print_spp_table(const json& r) {
  std::printf("\nsamples per pixel (relMSE = mean (v-ref)^2/(ref+0.01)^2)\n");
  std::printf("  %-12s %5s %9s %9s %10s %11s\n", "sampler", "spp", "seconds", "RMSE", "relMSE",
              "efficiency");
  for (const SamplerKind kind : kSamplers) {
    const std::string name = to_string(kind);
    for (const json& row : r["spp"][name]) {
      std::printf("  %-12s %5.0f %9.4f %9.5f %10.3e %11.4g\n", name.c_str(),
                  row["parameter"].get<double>(), row["seconds"].get<double>(),
                  row["rmse"].get<double>(), row["rel_mse"].get<double>(),
                  row["efficiency"].get<double>());
    }
  }
  const json& s = r["summary"];
  std::printf("  RMSE slope against spp (log-log, ideal -0.5 for independent samples):");
  for (const SamplerKind kind : kSamplers) {
    std::printf(" %s %.3f", to_string(kind).c_str(),
                s["rmse_slope"][to_string(kind)].get<double>());
  }
  std::printf("\n  against independent, relMSE ratio (median, spp >= 16):");
  for (const SamplerKind kind : {SamplerKind::Sobol, SamplerKind::PaddedSobol}) {
    const std::string name = to_string(kind);
    std::printf(" %s %.2fx at equal spp, %.2fx at equal time;", name.c_str(),
                s["equal_spp_factor"][name].get<double>(),
                s["equal_time_factor"][name].get<double>());
  }
  std::printf("\n");
}

void print_budget_table(const json& r) {
  const json& s = r["summary"];
  std::printf(
      "\nadaptive sampling on a budget (--adaptive: the time of N uniform spp, samples in "
      "proportion to sqrt(variance/cost))\n");
  std::printf("  %-12s %5s %9s %9s %10s %20s %11s\n", "sampler", "N", "mean spp", "seconds",
              "relMSE", "mean difference", "vs uniform");
  for (const SamplerKind kind : kSamplers) {
    const std::string name = to_string(kind);
    for (std::size_t i = 0; i < r["budget"][name].size(); ++i) {
      const json& row = r["budget"][name][i];
      std::printf("  %-12s %5.0f %9.1f %9.4f %10.3e %+9.5f +- %7.5f %10.2fx\n", name.c_str(),
                  row["parameter"].get<double>(), row["spp_mean"].get<double>(),
                  row["seconds"].get<double>(), row["rel_mse"].get<double>(),
                  row["mean_difference"].get<double>(), row["mean_difference_error"].get<double>(),
                  s["budget_equal_time_factors"][name][i]["factor"].get<double>());
    }
    std::printf("  %-12s median over N >= 32: %.2fx lower relMSE than uniform at equal time\n",
                name.c_str(), s["budget_equal_time_factor"][name].get<double>());
  }
}

// Rows of renders that stop at an error (--image-error, --target-error): what each reached,
// its bias, and its relMSE against its baseline's at equal time.
void print_error_rows(const json& rows, const json& factors, const char* factor_label) {
  std::printf("  %6s %9s %9s %10s %9s %20s %11s\n", "target", "mean spp", "seconds", "relMSE",
              "achieved", "mean difference", factor_label);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const json& row = rows[i];
    std::printf("  %6.3f %9.1f %9.4f %10.3e %9.4f %+9.5f +- %7.5f %10.2fx\n",
                row["parameter"].get<double>(), row["spp_mean"].get<double>(),
                row["seconds"].get<double>(), row["rel_mse"].get<double>(),
                row["achieved_error"].get<double>(), row["mean_difference"].get<double>(),
                row["mean_difference_error"].get<double>(), factors[i]["factor"].get<double>());
  }
}

void print_image_error_table(const json& r) {
  std::printf("\nimage error (--image-error with %s, at most %d spp per pixel)\n",
              r["image_error_sampler"].get<std::string>().c_str(), 4 * r["max_spp"].get<int>());
  print_error_rows(r["image_error"], r["summary"]["image_error_equal_time_factors"], "vs uniform");
}

void print_book_quality(const json& r) {
  const json& q = r["summary"]["book_quality"];
  std::printf(
      "\ntime to the book's quality (the relMSE of independent sampling at %d spp: %.3e; "
      "independent takes %.3f s)\n",
      q["book_spp"].get<int>(), q["rel_mse"].get<double>(), q["independent_seconds"].get<double>());
  for (const json& m : q["methods"]) {
    std::printf("  %-9s %-12s %9.3f s  %6.2fx less time  %6.2fx fewer rays\n",
                m["mode"].get<std::string>().c_str(), m["sampler"].get<std::string>().c_str(),
                m["seconds"].get<double>(), m["speedup"].get<double>(),
                m["ray_factor"].get<double>());
  }
}

void print_depth_table(const json& r) {
  std::printf(
      "\ndepth limit at %d spp (bias: image-sum difference from depth %d, +- its "
      "standard error)\n",
      r["fixed_spp"].get<int>(), r["depth"].get<int>());
  std::printf("  %5s %9s %10s %20s %10s %10s %10s\n", "depth", "seconds", "time saved",
              "mean difference", "RMS bias", "RMS noise", "relMSE");
  double full = 0, deepest = 0;  // the time at the deepest limit compared
  for (const json& row : r["depth_sweep"]) {
    if (row["parameter"].get<double>() > deepest) {
      deepest = row["parameter"].get<double>();
      full = row["seconds"].get<double>();
    }
  }
  for (const json& row : r["depth_sweep"]) {
    std::printf("  %5.0f %9.4f %9.0f%% %+9.5f +- %7.5f %10.5f %10.5f %10.3e\n",
                row["parameter"].get<double>(), row["seconds"].get<double>(),
                100.0 * (1.0 - row["seconds"].get<double>() / full),
                row["mean_difference"].get<double>(), row["mean_difference_error"].get<double>(),
                row["rms_bias"].get<double>(), row["rms_noise"].get<double>(),
                row["rel_mse"].get<double>());
  }
}

void print_choice_tables(const json& r) {
  std::printf("\nintersector at %d spp\n", r["fixed_spp"].get<int>());
  for (const json& row : r["intersector"]) {
    std::printf("  %-7s %9.4f s  relMSE %.4e%s\n", row["choice"].get<std::string>().c_str(),
                row["seconds"].get<double>(), row["rel_mse"].get<double>(),
                row.contains("identical_to_embree")
                    ? (row["identical_to_embree"].get<bool>() ? "  (bit-identical to embree)"
                                                              : "  (DIFFERS from embree)")
                    : "");
  }

  std::printf("\nglass Fresnel at %d spp (the reference uses the scene's: schlick)\n",
              4 * r["fixed_spp"].get<int>());
  for (const json& row : r["fresnel"]) {
    std::printf("  %-7s %9.4f s  mean difference %+.5f +- %.5f  RMS bias %.5f  relMSE %.4e\n",
                row["choice"].get<std::string>().c_str(), row["seconds"].get<double>(),
                row["mean_difference"].get<double>(), row["mean_difference_error"].get<double>(),
                row["rms_bias"].get<double>(), row["rel_mse"].get<double>());
  }
}

void print_adaptive_table(const json& r) {
  std::printf("\nadaptive sampling (--target-error, min 16 spp, at most %d)\n",
              4 * r["max_spp"].get<int>());
  print_error_rows(r["adaptive"], r["summary"]["adaptive_equal_time_factors"], "equal-time");
  std::printf(
      "  (achieved = sqrt(relMSE); equal-time = independent's relMSE at the same time / "
      "adaptive's)\n");
}

void print_table(const json& r) {
  std::printf("%s %dx%d, reference %d spp (seed %llu)%s\n", r["scene"].get<std::string>().c_str(),
              r["width"].get<int>(), r["height"].get<int>(), r["reference_spp"].get<int>(),
              r["reference_seed"].get<unsigned long long>(),
              r["reference_reused"].get<bool>() ? ", reused from the cache" : "");
  print_spp_table(r);
  print_budget_table(r);
  print_image_error_table(r);
  print_book_quality(r);
  print_depth_table(r);
  print_choice_tables(r);
  print_adaptive_table(r);
}

void write_csv(const json& r, const std::string& path) {
  const char* keys[] = {
      "group",    "choice",   "parameter", "spp_mean",   "depth",           "seconds",
      "rays",     "rmse",     "rel_mse",   "efficiency", "mean_difference", "mean_difference_error",
      "rms_bias", "rms_noise"};
  std::string text;
  for (const char* k : keys) text.append(text.empty() ? "" : ",").append(k);
  text += "\n";
  std::vector<const json*> rows;
  for (const char* group : {"spp", "budget"}) {
    for (const SamplerKind kind : kSamplers) {
      for (const json& row : r[group][to_string(kind)]) rows.push_back(&row);
    }
  }
  for (const char* group : {"image_error", "depth_sweep", "intersector", "fresnel", "adaptive"}) {
    for (const json& row : r[group]) rows.push_back(&row);
  }
  for (const json* row : rows) {
    std::string line;
    for (const char* k : keys) {
      const json& v = (*row)[k];
      line.append(line.empty() ? "" : ",").append(v.is_string() ? v.get<std::string>() : v.dump());
    }
    text += line + "\n";
  }
  write_text_atomically(path, text);
}

// Every option checked before the reference (minutes of rendering) is made. The sample
// counts' limits depend on each other, so every one broken is named in the one line.
void check_options(const AccuracyOptions& o) {
  if (o.width < 1) throw InvalidInput("--width must be >= 1");
  std::vector<std::string> spp_problems;
  if (o.max_spp < 64) {
    spp_problems.push_back("--max-spp must be >= 64 (the fits and the budget sweep start at " +
                           std::string("16-32), got ") + std::to_string(o.max_spp));
  }
  if (std::int64_t(o.reference_spp) < 4 * std::int64_t(std::max(o.max_spp, 64))) {
    spp_problems.push_back("--reference-spp must be at least 4x --max-spp (" +
                           std::to_string(4 * std::int64_t(std::max(o.max_spp, 64))) +
                           ", or its noise swamps the errors), got " +
                           std::to_string(o.reference_spp));
  }
  if (o.fixed_spp < 2) {
    spp_problems.push_back("--fixed-spp must be >= 2, got " + std::to_string(o.fixed_spp));
  }
  if (o.book_spp < 16) {
    spp_problems.push_back("--book-spp must be >= 16, got " + std::to_string(o.book_spp));
  }
  if (!spp_problems.empty()) {
    std::string text;
    for (const std::string& p : spp_problems) text += (text.empty() ? "" : "; ") + p;
    throw InvalidInput(text);
  }
  // The two directories: missing ones are made, but a path that is a file is refused.
  check_output_directory(o.out_dir, "--out");
  if (!o.cache_dir.empty()) check_output_directory(o.cache_dir, "--cache-dir");
  if (o.repeat < 1) throw InvalidInput("--repeat must be >= 1");
  if (o.depths.empty() || *std::min_element(o.depths.begin(), o.depths.end()) < 1) {
    throw InvalidInput("--depths must list depth limits >= 1");
  }
  for (const double e : o.target_errors) {
    if (!(e > 0) || !std::isfinite(e)) throw InvalidInput("--target-errors must be > 0");
  }
  for (const double e : o.image_errors) {
    if (!(e > 0) || !std::isfinite(e)) throw InvalidInput("--image-errors must be > 0");
  }
}

// The measured renders' settings: the scene's depth and aspect ratio at the given width.
RenderSettings base_settings(const AccuracyOptions& o, const Scene& scene) {
  RenderSettings base;
  base.width = o.width;
  base.height = int(std::min(height_for_width(o.width, scene.image.aspect_ratio), 1e9));
  base.max_depth = scene.image.max_depth;
  base.threads = o.threads;
  base.seed = o.seed;
  base.sampler = SamplerKind::Independent;  // the reference's and the comparisons'
  base.samples = FixedSamples{o.reference_spp};
  validate(base);
  return base;
}

// The seconds (or rays) a sweep needs to reach `rel_mse`, from its fit (spp >= 16: the
// regime of the goal, where every sampler's slope has settled).
double cost_to_reach(const json& rows, const char* cost, double rel_mse) {
  const auto [slope, intercept] = error_cost_fit(rows, cost, 16);
  return std::exp((std::log(rel_mse) - intercept) / slope);
}

// The headline: the relMSE independent sampling reaches at the book's spp (from the fit of
// relMSE against spp), and how long each method takes to reach it.
json book_quality(const json& r, int book_spp) {
  const json& independent = r["spp"]["independent"];
  std::vector<double> spp, e;
  for (const json& row : independent) {
    if (row["parameter"].get<double>() >= 16) {
      spp.push_back(row["parameter"].get<double>());
      e.push_back(row["rel_mse"].get<double>());
    }
  }
  const auto [slope, intercept] = log_log_fit(spp, e);
  const double goal = std::exp(intercept + slope * std::log(double(book_spp)));
  const double baseline = cost_to_reach(independent, "seconds", goal);
  const double baseline_rays = cost_to_reach(independent, "rays", goal);
  json q = {{"book_spp", book_spp}, {"rel_mse", goal}, {"independent_seconds", baseline}};
  json methods = json::array();
  for (const auto& [group, label] :
       {std::pair<const char*, const char*>{"spp", "uniform"}, {"budget", "adaptive"}}) {
    for (const SamplerKind kind : kSamplers) {
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

// The ratios a reader looks for: convergence slopes, each sampler's gain over independent
// sampling at equal spp and at equal time, adaptive sampling's over uniform sampling with the
// same sampler, and the time to the book's quality.
json summarise(const json& r, const AccuracyOptions& o) {
  json s;
  const json& independent = r["spp"]["independent"];
  for (const SamplerKind kind : kSamplers) {
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
  for (const SamplerKind kind : kSamplers) {
    const std::string name = to_string(kind);
    s["budget_equal_time_factors"][name] = equal_time_factors(r["spp"][name], r["budget"][name]);
    s["budget_equal_time_factor"][name] = median_factor(s["budget_equal_time_factors"][name], 32);
  }
  s["adaptive_equal_time_factors"] = equal_time_factors(independent, r["adaptive"]);
  s["image_error_equal_time_factors"] =
      equal_time_factors(r["spp"][r["image_error_sampler"].get<std::string>()], r["image_error"]);
  s["book_quality"] = book_quality(r, o.book_spp);
  return s;
}

void write_figures(const AccuracyOptions& o, const json& r) {
  const std::string json_path = (fs::path(o.out_dir) / "accuracy.json").string();
  const std::string csv_path = (fs::path(o.out_dir) / "accuracy.csv").string();
  const std::string png_path = (fs::path(o.out_dir) / "accuracy.png").string();
  write_text_atomically(json_path, r.dump(2) + "\n");
  write_csv(r, csv_path);
  std::printf("\nfigures: %s\n         %s\n", one_line(json_path).c_str(),
              one_line(csv_path).c_str());
  run_plot_script("accuracy_plot.py", json_path, png_path);
}

int run_accuracy(const AccuracyOptions& o) {
  check_options(o);
  const Scene scene = make_builtin_scene(o.scene, o.scene_seed);
  const RenderSettings base = base_settings(o, scene);
  fs::create_directories(o.out_dir);
  const std::string cache_dir = o.cache_dir.empty() ? default_cache_dir() : o.cache_dir;

  RenderSettings reference_settings = base;
  reference_settings.seed = kReferenceSeed;
  const Reference reference =
      load_or_render_reference(scene, reference_settings, cache_dir, o.quiet);
  if (!o.quiet && reference.reused) {
    std::fprintf(stderr, "accuracy: reusing the reference %s\n", reference.path.c_str());
  }
  const Experiment x(o, scene, base, reference.image);

  json r = {{"scene", scene.name},
            {"width", base.width},
            {"height", base.height},
            {"depth", base.max_depth},
            {"seed", o.seed},
            {"reference_spp", o.reference_spp},
            {"reference_seed", kReferenceSeed},
            {"reference_path", reference.path},
            {"reference_reused", reference.reused},
            {"fixed_spp", o.fixed_spp},
            {"max_spp", o.max_spp},
            {"repeat", o.repeat},
            {"threads", o.threads}};
  for (const SamplerKind kind : kSamplers) r["spp"][to_string(kind)] = sweep_spp(x, o, kind);
  for (const SamplerKind kind : kSamplers)
    r["budget"][to_string(kind)] = sweep_spp(x, o, kind, true);
  r["image_error_sampler"] = to_string(SamplerKind::Sobol);
  r["image_error"] = sweep_image_error(x, o, SamplerKind::Sobol);
  r["depth_sweep"] = sweep_depth(x, o);
  r["intersector"] = compare_intersectors(x, o);
  r["fresnel"] = compare_fresnel(x, o, scene);
  r["adaptive"] = sweep_adaptive(x, o);

  r["summary"] = summarise(r, o);
  print_table(r);
  write_figures(o, r);
  return 0;
}

}  // namespace

std::function<int()> add_accuracy_command(CLI::App& app) {
  auto options = std::make_shared<AccuracyOptions>();
  AccuracyOptions& o = *options;
  CLI::App* cmd = app.add_subcommand(
      "accuracy",
      "Measure speed against accuracy on a scene: error against a cached high-spp reference "
      "for spp 1..N with each sampler, adaptive sampling (budget, image error, target error), "
      "the time to the book's quality, the depth limit, the intersector and the Fresnel "
      "model; prints tables, writes JSON, CSV and a PNG plot (about 9 minutes on a 2-core "
      "machine, the reference cached after the first run; --quick: a few seconds)");
  cmd->add_option("--scene", o.scene, "Built-in scene")->capture_default_str();
  cmd->add_option("--scene-seed", o.scene_seed, "Seed of the scene's random layout")
      ->check(kNotNegative)
      ->capture_default_str();
  cmd->add_option("--width", o.width, "Image width (height from the scene's aspect ratio)")
      ->capture_default_str();
  cmd->add_option("--reference-spp", o.reference_spp,
                  "Samples per pixel of the reference, at least 4x --max-spp")
      ->capture_default_str();
  cmd->add_option("--max-spp", o.max_spp,
                  "Largest spp of the sweep (1, 2, 4, ... up to it), at least 64")
      ->capture_default_str();
  cmd->add_option("--fixed-spp", o.fixed_spp,
                  "Spp of the depth and intersector comparisons (Fresnel: 4x this), at least 2")
      ->capture_default_str();
  cmd->add_option("--depths", o.depths, "Depth limits to compare")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--target-errors", o.target_errors, "Adaptive sampling targets to compare")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--image-errors", o.image_errors, "Image errors (--image-error) to compare")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--book-spp", o.book_spp,
                  "The spp whose independent-sampling error is the goal of the time-to-quality "
                  "headline (the book's final render: 500), at least 16")
      ->capture_default_str();
  cmd->add_option("--seed", o.seed, "Seed of the measured renders")
      ->check(kNotNegative)
      ->capture_default_str();
  cmd->add_option("--threads", o.threads, "Worker threads (0: all cores)")->capture_default_str();
  cmd->add_option("--repeat", o.repeat,
                  "Renders per measurement; the median time is kept (the image is the same)")
      ->capture_default_str();
  cmd->add_option("--out", o.out_dir, "Directory for accuracy.json, accuracy.csv, accuracy.png")
      ->capture_default_str();
  cmd->add_option("--cache-dir", o.cache_dir,
                  "Where references are kept (default: $XDG_CACHE_HOME/rtiow or ~/.cache/rtiow)");
  cmd->add_flag("-q,--quiet", o.quiet, "No progress on stderr");
  cmd->add_flag("--quick", o.quick,
                "A short run for a first look: 80 px wide, a reference of 1024 spp, spp up to "
                "256, fewer depths and targets, one run each (options given still apply)");
  return [options, cmd] {
    if (!cmd->parsed()) return -1;
    if (options->quick) {
      apply_quick_run(*cmd, {{"--width", "80"},
                             {"--reference-spp", "1024"},
                             {"--max-spp", "256"},
                             {"--fixed-spp", "16"},
                             {"--book-spp", "64"},
                             {"--depths", "1,2,4,8,50"},
                             {"--target-errors", "0.2,0.1"},
                             {"--image-errors", "0.1,0.05"},
                             {"--repeat", "1"}});
    }
    return run_accuracy(*options);
  };
}

}  // namespace rtiow
