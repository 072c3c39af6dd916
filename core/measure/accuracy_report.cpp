#include "core/measure/accuracy_report.h"
#include "core/limits/setting_name.h"

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/limits/error.h"
#include "core/measure/accuracy_fits.h"
#include "core/measure/plot_script.h"
#include "core/measure/timing_warnings.h"

namespace rtiow {
namespace {

namespace fs = std::filesystem;
using json = Figures;

void print_spp_table(const json& r) {
  std::printf("\nsamples per pixel (relMSE = mean (v-ref)^2/(ref+0.01)^2)\n");
  std::printf("  %-12s %5s %9s %9s %10s %11s\n", "sampler", "spp", "seconds", "RMSE", "relMSE",
              "efficiency");
  for (const SamplerKind kind : kAccuracySamplers) {
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
  for (const SamplerKind kind : kAccuracySamplers) {
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
      "\nadaptive sampling on a budget (%s: the time of N uniform spp, samples in "
      "proportion to sqrt(variance/cost))\n",
      setting("adaptive").c_str());
  std::printf("  %-12s %5s %9s %9s %10s %20s %11s\n", "sampler", "N", "mean spp", "seconds",
              "relMSE", "mean difference", "vs uniform");
  for (const SamplerKind kind : kAccuracySamplers) {
    const std::string name = to_string(kind);
    for (std::size_t i = 0; i < r["budget"][name].size(); ++i) {
      const json& row = r["budget"][name][i];
      // A render of one sequence estimates no error: its difference stands without one.
      const json& error = row["mean_difference_error"];
      char difference[32];
      if (error.is_null()) {
        std::snprintf(difference, sizeof difference, "%+9.5f           ",
                      row["mean_difference"].get<double>());
      } else {
        std::snprintf(difference, sizeof difference, "%+9.5f +- %7.5f",
                      row["mean_difference"].get<double>(), error.get<double>());
      }
      std::printf("  %-12s %5.0f %9.1f %9.4f %10.3e %s %10.2fx\n", name.c_str(),
                  row["parameter"].get<double>(), row["spp_mean"].get<double>(),
                  row["seconds"].get<double>(), row["rel_mse"].get<double>(), difference,
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
  std::printf("\nimage error (%s with %s, at most %d spp per pixel)\n",
              setting("image_error").c_str(), r["image_error_sampler"].get<std::string>().c_str(),
              4 * r["max_spp"].get<int>());
  print_error_rows(r["image_error"], r["summary"]["image_error_equal_time_factors"], "vs uniform");
}

// --denoise against the same sampler's uniform renders at equal time, and the error the
// denoiser reported beside the error it delivered.
void print_denoised_table(const json& r) {
  std::printf("\ndenoised (%s, %s with %s; seconds: the render's and the denoiser's)\n",
              setting("denoise").c_str(), setting("spp").c_str(),
              r["denoised_sampler"].get<std::string>().c_str());
  std::printf("  %6s %9s %9s %10s %9s %9s %11s\n", "spp", "seconds", "denoise", "relMSE",
              "achieved", "reported", "vs uniform");
  const json& factors = r["summary"]["denoised_equal_time_factors"];
  for (std::size_t i = 0; i < r["denoised"].size(); ++i) {
    const json& row = r["denoised"][i];
    std::printf("  %6.0f %9.4f %9.4f %10.3e %9.4f %9.4f %10.2fx\n", row["parameter"].get<double>(),
                row["seconds"].get<double>(), row["denoise_seconds"].get<double>(),
                row["rel_mse"].get<double>(), row["achieved_error"].get<double>(),
                row["estimated_error"].get<double>(), factors[i]["factor"].get<double>());
  }
}

void print_book_quality(const json& r) {
  const json& q = r["summary"]["book_quality"];
  std::printf(
      "\ntime to the book's quality (the relMSE of the book's estimator, independent sampling "
      "without Russian roulette, at %d spp: %.3e; it takes %.3f s)\n",
      q["book_spp"].get<int>(), q["rel_mse"].get<double>(), q["book_seconds"].get<double>());
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
  std::vector<double> depths, seconds;
  for (const json& row : r["depth_sweep"]) {
    depths.push_back(row["parameter"].get<double>());
    seconds.push_back(row["seconds"].get<double>());
    std::printf("  %5.0f %9.4f %9.0f%% %+9.5f +- %7.5f %10.5f %10.5f %10.3e\n",
                row["parameter"].get<double>(), row["seconds"].get<double>(),
                100.0 * (1.0 - row["seconds"].get<double>() / full),
                row["mean_difference"].get<double>(), row["mean_difference_error"].get<double>(),
                row["rms_bias"].get<double>(), row["rms_noise"].get<double>(),
                row["rel_mse"].get<double>());
  }
  if (const std::string warning = depth_timing_warning(depths, seconds); !warning.empty()) {
    std::fprintf(stderr, "rtiow: %s\n", warning.c_str());  // the table stays the figures
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
  std::printf("\nadaptive sampling (%s, min 16 spp, at most %d)\n", setting("target_error").c_str(),
              4 * r["max_spp"].get<int>());
  print_error_rows(r["adaptive"], r["summary"]["adaptive_equal_time_factors"], "equal-time");
  std::printf(
      "  (achieved = sqrt(relMSE); equal-time = independent's relMSE at the same time / "
      "adaptive's)\n");
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
    for (const SamplerKind kind : kAccuracySamplers) {
      for (const json& row : r[group][to_string(kind)]) rows.push_back(&row);
    }
  }
  for (const char* group :
       {"book", "image_error", "depth_sweep", "intersector", "fresnel", "adaptive", "denoised"}) {
    for (const json& row : r[group]) rows.push_back(&row);
  }
  for (const json* row : rows) {
    std::string line;
    for (const char* k : keys) {
      const json& v = (*row)[k];
      line.append(line.empty() ? "" : ",")
          .append(v.is_string() ? v.get<std::string>() : figures_text(v));
    }
    text += line + "\n";
  }
  write_text_atomically(path, text);
}

}  // namespace

void print_table(const json& r) {
  std::printf("%s %dx%d, reference %d spp (seed %llu)%s\n", r["scene"].get<std::string>().c_str(),
              r["width"].get<int>(), r["height"].get<int>(), r["reference_spp"].get<int>(),
              r["reference_seed"].get<unsigned long long>(),
              r["reference_reused"].get<bool>() ? ", reused from the cache" : "");
  print_spp_table(r);
  print_budget_table(r);
  print_image_error_table(r);
  print_denoised_table(r);
  print_book_quality(r);
  print_depth_table(r);
  print_choice_tables(r);
  print_adaptive_table(r);
}

MeasureFiles write_figures(const AccuracyOptions& o, const json& r) {
  const std::string json_path = (fs::path(o.out_dir) / "accuracy.json").string();
  const std::string csv_path = (fs::path(o.out_dir) / "accuracy.csv").string();
  const std::string png_path = (fs::path(o.out_dir) / "accuracy.png").string();
  write_text_atomically(json_path, figures_text(r, 2) + "\n");
  write_csv(r, csv_path);
  std::printf("\nfigures: %s\n         %s\n", one_line(json_path).c_str(),
              one_line(csv_path).c_str());
  const bool plotted = run_plot_script("accuracy_plot.py", figures_text(r), png_path);
  return {json_path, csv_path, plotted ? png_path : std::string()};
}

}  // namespace rtiow
