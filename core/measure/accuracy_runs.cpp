#include "core/measure/accuracy_runs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/denoise/denoiser.h"
#include "core/render/denoised_output.h"
#include "core/render/render.h"
#include "core/render/render_statistics.h"

namespace rtiow {
namespace {

using json = Figures;

constexpr SamplerKind kDenoisedSampler = RenderRequest{}.sampler;

// One measured render: its image error against the reference and its median time.
struct Trial {
  json row;
  RenderResult result;
};

// What a trial measures of its render: the image itself, or what a step after the render makes
// of it (the denoiser), with that step's seconds and figures of its own for the row.
struct Delivered {
  ImageEstimate image;
  double seconds = 0.0;
  json figures = json::object();
};
using Deliver = std::function<Delivered(const RenderResult&)>;

class Experiment {
 public:
  Experiment(const AccuracyOptions& o, const Scene& scene, const RenderRequest& base,
             const ImageEstimate& reference)
      : o_(o), scene_(scene), base_(base), reference_(reference) {}

  // Renders `repeat` times (the image is the same each time; only the time varies) and
  // measures the first against the reference.
  Trial run(const std::string& group, const std::string& choice, double parameter,
            const RenderRequest& request, const Deliver& deliver = {}) const {
    const ResolvedRender job = resolve(scene_, request);
    const RenderSettings& settings = job.settings;
    std::vector<double> seconds;
    Trial trial;
    for (int i = 0; i < o_.repeat; ++i) {
      RenderResult r = render(job.scene, settings);
      seconds.push_back(r.render_seconds);
      if (i == 0) trial.result = std::move(r);
    }
    std::sort(seconds.begin(), seconds.end());
    const Delivered delivered =
        deliver ? deliver(trial.result) : Delivered{to_estimate(trial.result)};
    const double median = seconds[seconds.size() / 2] + delivered.seconds;
    const ImageError e = measure_error(delivered.image, reference_);
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
    // One sequence (--adaptive where no error is asked) has no estimate of its error: the
    // reference's alone would understate the difference's.
    if (trial.result.replicates < kReplicates) trial.row["mean_difference_error"] = nullptr;
    trial.row.update(delivered.figures);
    if (!o_.quiet) {
      std::fprintf(stderr, "accuracy: %-10s %-12s %8g: %7.3f s, relMSE %.3g\n", group.c_str(),
                   choice.c_str(), parameter, median, e.rel_mse);
    }
    return trial;
  }

  RenderRequest request() const { return base_; }

 private:
  const AccuracyOptions& o_;
  const Scene& scene_;
  const RenderRequest base_;
  const ImageEstimate& reference_;
};

// Uniform sampling at spp 1, 2, 4, ... max_spp; or --adaptive on the budget of 32..max_spp
// uniform samples (16 is the minimum every pixel takes).
json sweep_spp(const Experiment& x, const AccuracyOptions& o, SamplerKind sampler,
               bool adaptive = false) {
  json rows = json::array();
  for (int spp = adaptive ? 32 : 1; spp <= o.max_spp; spp *= 2) {
    RenderRequest s = x.request();
    s.spp = spp, s.adaptive = adaptive, s.sampler = sampler;
    rows.push_back(x.run(adaptive ? "budget" : "spp", to_string(sampler), spp, s).row);
  }
  return rows;
}

// The book's estimator: independent numbers and every path to its depth (no Russian
// roulette), the baseline of the time to the book's quality.
json sweep_book(const Experiment& x, const AccuracyOptions& o) {
  json rows = json::array();
  for (int spp = 1; spp <= o.max_spp; spp *= 2) {
    RenderRequest s = x.request();
    s.spp = spp, s.sampler = SamplerKind::Independent, s.russian_roulette = false;
    rows.push_back(x.run("book", "independent without roulette", spp, s).row);
  }
  return rows;
}

json sweep_image_error(const Experiment& x, const AccuracyOptions& o, SamplerKind sampler) {
  json rows = json::array();
  for (const double target : o.image_errors) {
    RenderRequest s = x.request();
    s.image_error = target, s.spp = 4 * o.max_spp, s.sampler = sampler;
    Trial t = x.run("image_error", to_string(sampler), target, s);
    t.row["achieved_error"] = std::sqrt(t.row["rel_mse"].get<double>());
    rows.push_back(t.row);
  }
  return rows;
}

json sweep_depth(const Experiment& x, const AccuracyOptions& o) {
  json rows = json::array();
  for (const int depth : o.depths) {
    RenderRequest s = x.request();
    s.spp = o.fixed_spp, s.max_depth = depth;
    rows.push_back(x.run("depth", "independent", depth, s).row);
  }
  return rows;
}

// Embree against the naive loop: the same sphere test, so the same image is expected.
json compare_intersectors(const Experiment& x, const AccuracyOptions& o) {
  json rows = json::array();
  RenderRequest s = x.request();
  s.spp = o.fixed_spp;
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
json compare_fresnel(const Experiment& x, const AccuracyOptions& o) {
  json rows = json::array();
  RenderRequest s = x.request();
  s.spp = 4 * o.fixed_spp;
  for (const FresnelModel model : {FresnelModel::Schlick, FresnelModel::Exact}) {
    s.fresnel = model;
    rows.push_back(x.run("fresnel", std::string(to_string(model)), 4 * o.fixed_spp, s).row);
  }
  return rows;
}

// --denoise at 2, 4, ... max_spp with the command line's default sampler (Sobol): the denoised
// image's error against the reference beside the error the denoiser reports, its time the render's
// and the denoiser's. The denoised image has no variances: its error is partly bias, and all of it
// counts here.
json sweep_denoised(const Experiment& x, const AccuracyOptions& o) {
  const Deliver denoised = [](const RenderResult& r) {
    const DenoisedImage d = denoise(denoise_input(r));
    return Delivered{{d.image, {}},
                     d.seconds,
                     {{"denoise_seconds", d.seconds},
                      {"estimated_error", d.estimated_error},
                      {"noisy_estimated_error", d.noisy_error}}};
  };
  json rows = json::array();
  for (int spp = 2; spp <= o.max_spp; spp *= 2) {
    RenderRequest s = x.request();
    s.spp = spp, s.sampler = kDenoisedSampler, s.estimate_error = true;
    s.passes = {true, true, true};
    Trial t = x.run("denoised", to_string(s.sampler) + " --denoise", spp, s, denoised);
    t.row["achieved_error"] = std::sqrt(t.row["rel_mse"].get<double>());
    rows.push_back(t.row);
  }
  return rows;
}

json sweep_adaptive(const Experiment& x, const AccuracyOptions& o) {
  json rows = json::array();
  for (const double target : o.target_errors) {
    RenderRequest s = x.request();
    s.target_error = target, s.spp = 4 * o.max_spp;
    Trial t = x.run("adaptive", "independent", target, s);
    t.row["achieved_error"] = std::sqrt(t.row["rel_mse"].get<double>());
    rows.push_back(t.row);
  }
  return rows;
}

}  // namespace

void run_sweeps(const AccuracyOptions& o, const Scene& scene, const RenderRequest& base,
                const ImageEstimate& reference, json& r) {
  const Experiment x(o, scene, base, reference);
  r["book"] = sweep_book(x, o);
  for (const SamplerKind kind : kAccuracySamplers)
    r["spp"][to_string(kind)] = sweep_spp(x, o, kind);
  for (const SamplerKind kind : kAccuracySamplers)
    r["budget"][to_string(kind)] = sweep_spp(x, o, kind, true);
  r["image_error_sampler"] = to_string(SamplerKind::Sobol);
  r["image_error"] = sweep_image_error(x, o, SamplerKind::Sobol);
  r["depth_sweep"] = sweep_depth(x, o);
  r["intersector"] = compare_intersectors(x, o);
  r["fresnel"] = compare_fresnel(x, o);
  r["adaptive"] = sweep_adaptive(x, o);
  r["denoised_sampler"] = to_string(kDenoisedSampler);
  r["denoised"] = sweep_denoised(x, o);
}

}  // namespace rtiow
