// The denoiser's study (docs/denoising.md): the error it reports against the error it delivers,
// and the time it takes to reach the default image's error.
//
//   rtiow_denoise_study calibrate SCENE WIDTH REFERENCE_SPP SEEDS SPP...
//   rtiow_denoise_study calibrate-adaptive SCENE WIDTH REFERENCE_SPP SEEDS SPP...  (--adaptive)
//   rtiow_denoise_study trade SCENE WIDTH REFERENCE_SPP
//   rtiow_denoise_study target SCENE WIDTH REFERENCE_SPP SEEDS ERROR...
//
// The truth is a render of REFERENCE_SPP with another seed, its own variance (from its halves)
// taken out of the squared error. Relative errors use rtiow's offset of 0.01.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "core/denoise/denoiser.h"
#include "core/render/denoised_output.h"
#include "core/render/render.h"
#include "core/scene/builtin_scenes.h"
#include "tests/reference_error.h"

namespace rtiow {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

RenderSettings denoise_settings(int width, int height, int spp, std::uint64_t seed) {
  RenderSettings s;
  s.width = width, s.height = height, s.samples = FixedSamples{spp}, s.seed = seed;
  s.estimate_error = true, s.passes = {true, true, true};
  return s;
}

// A reference and the true relative squared error of images against it.
struct Reference {
  DenoiseInput sums;
  int width = 0;

  // Summed over the pixels [x0, x1) x [y0, y1) and their channels.
  double squared_error(const std::vector<Color>& image, int x0, int y0, int x1, int y1) const {
    return true_relative_squared_error(sums, image, x0, y0, x1, y1);
  }
  double image_error(const std::vector<Color>& image) const {
    const int height = int(sums.size() / std::size_t(width));
    return std::sqrt(
        std::max(0.0, squared_error(image, 0, 0, width, height) / (3.0 * double(sums.size()))));
  }
};

Reference reference_of(const Scene& scene, int width, int height, int spp) {
  return {denoise_input(render(scene, denoise_settings(width, height, spp, 999))), width};
}

// The per-pixel error channel against the truth in 32x32 blocks, each read relative to the
// denoised image as a user of the file would: how many blocks' true error is over twice their
// estimate, how many under half of it, and the channel's total over the true total.
struct BlockReading {
  int over = 0, under = 0, blocks = 0;
  double estimate = 0, truth = 0;
};
BlockReading blocks_against_estimate(const Reference& ref, const DenoisedImage& d) {
  BlockReading b;
  const int w = d.image.width(), h = d.image.height();
  for (int by = 0; by + 32 <= h; by += 32) {
    for (int bx = 0; bx + 32 <= w; bx += 32) {
      const double truth = ref.squared_error(d.image.pixels(), bx, by, bx + 32, by + 32);
      const double estimate = channel_relative_squared_error(d, bx, by, bx + 32, by + 32);
      ++b.blocks, b.over += truth > 2 * estimate ? 1 : 0, b.under += estimate > 2 * truth ? 1 : 0;
      b.estimate += estimate, b.truth += truth;
    }
  }
  return b;
}

// `adaptive`: each count is an adaptive budget as `--adaptive --spp N --denoise` renders it, each
// pixel at least the command's default minimum (--min-spp 16).
void calibrate(const Scene& scene, int width, int height, int reference_spp, int seeds,
               const std::vector<int>& counts, bool adaptive) {
  const Reference ref = reference_of(scene, width, height, reference_spp);
  for (const int spp : counts) {
    for (int seed = 1; seed <= seeds; ++seed) {
      RenderSettings settings = denoise_settings(width, height, spp, std::uint64_t(seed));
      if (adaptive) settings.samples = AdaptiveBudget{spp, kDefaultLeastSamples};
      const RenderResult r = render(scene, settings);
      const DenoisedImage d = denoise(denoise_input(r));
      const double truth = ref.image_error(d.image.pixels());
      const double noisy = ref.image_error(r.film.pixels());
      const BlockReading b = blocks_against_estimate(ref, d);
      // The noisy value's share in the image, and the true squared error's share in the
      // pixels that kept more than half of it: where more gain would have to come from.
      double share = 0, kept_error = 0, all_error = 0;
      for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
          const double e = ref.squared_error(d.image.pixels(), x, y, x + 1, y + 1);
          const double kept = d.noisy_kept[std::size_t(y) * std::size_t(width) + std::size_t(x)];
          share += kept, all_error += e, kept_error += kept > 0.5 ? e : 0.0;
        }
      }
      std::printf(
          "%s %dx%d spp %d seed %d: denoised est %.5f true %.5f ratio %.3f | noisy est %.5f "
          "true %.5f | mse gain %.2f | noisy share %.1f%% (%.0f%% of the true error) | blocks bad "
          "%d/%d, over-read %d, channel over truth %.2f | %.2fs\n",
          scene.name.c_str(), width, height, spp, seed, d.estimated_error, truth,
          d.estimated_error / truth, d.noisy_error, noisy, noisy * noisy / (truth * truth),
          100.0 * share / double(d.noisy_kept.size()), 100.0 * kept_error / all_error, b.over,
          b.blocks, b.under, b.estimate / b.truth, d.seconds);
    }
  }
}

// One curve of the trade: a count's true error and the seconds it took, render and denoising.
struct TradePoint {
  int spp;
  double error, seconds;
};

// Where a curve reaches `error`: between the two counts around it, the error as spp^-k and the
// seconds linear in the count. "already" where its first count is below it, "not reached" where
// its last is above.
void print_crossing(const char* name, const std::vector<TradePoint>& curve, double error,
                    double default_seconds) {
  if (curve.front().error <= error) {
    std::printf("  %s: below it already at %d spp, %.3f s: %.2fx\n", name, curve.front().spp,
                curve.front().seconds, default_seconds / curve.front().seconds);
    return;
  }
  for (std::size_t i = 0; i + 1 < curve.size(); ++i) {
    const TradePoint& a = curve[i];
    const TradePoint& b = curve[i + 1];
    if (b.error > error) continue;
    const double k = std::log(a.error / b.error) / std::log(double(b.spp) / double(a.spp));
    const double spp = a.spp * std::pow(a.error / error, 1.0 / k);
    const double seconds = a.seconds + (b.seconds - a.seconds) * (spp - a.spp) / (b.spp - a.spp);
    std::printf("  %s: reaches it at %.0f spp, %.3f s: %.2fx\n", name, spp, seconds,
                default_seconds / seconds);
    return;
  }
  std::printf("  %s: not reached by %d spp\n", name, curve.back().spp);
}

void trade(const Scene& scene, int width, int height, int reference_spp) {
  const Reference ref = reference_of(scene, width, height, reference_spp);
  RenderSettings plain;  // the default image: one Sobol sequence, no passes
  plain.width = width, plain.height = height, plain.samples = FixedSamples{100};
  double error = 0, fastest = 1e30;
  for (int seed = 1; seed <= 3; ++seed) {
    plain.seed = std::uint64_t(seed);
    const auto start = std::chrono::steady_clock::now();
    const RenderResult r = render(scene, plain);
    fastest = std::min(fastest, seconds_since(start));
    error += ref.image_error(r.film.pixels()) / 3;
  }
  std::printf("%s %dx%d: default 100 spp: true error %.5f, %.3f s (fastest of 3)\n",
              scene.name.c_str(), width, height, error, fastest);
  std::vector<TradePoint> denoised_curve, adaptive_curve, adaptive_denoised_curve;
  for (const int spp : {8, 16, 32, 64, 100}) {
    double denoised = 0, noisy = 0, render_s = 1e30, denoise_s = 1e30;
    for (int seed = 1; seed <= 2; ++seed) {
      const auto start = std::chrono::steady_clock::now();
      const RenderResult r =
          render(scene, denoise_settings(width, height, spp, std::uint64_t(seed)));
      render_s = std::min(render_s, seconds_since(start));
      const DenoisedImage d = denoise(denoise_input(r));
      denoise_s = std::min(denoise_s, d.seconds);
      denoised += ref.image_error(d.image.pixels()) / 2,
          noisy += ref.image_error(r.film.pixels()) / 2;
    }
    std::printf(
        "  --denoise %3d spp: true error %.5f (noisy %.5f), render %.3f s + denoise %.3f s = "
        "%.3f s\n",
        spp, denoised, noisy, render_s, denoise_s, render_s + denoise_s);
    denoised_curve.push_back({spp, denoised, render_s + denoise_s});
  }
  // Adaptive budgets, each pixel at least a quarter of the budget (--min-spp N/4: the command's
  // default of 16 would leave budgets of 8 and 16 nothing to allocate):
  // alone (one sequence, as --adaptive renders without --denoise) and denoised.
  for (const int spp : {8, 16, 32, 64, 100}) {
    double alone = 0, denoised = 0, alone_s = 1e30, render_s = 1e30, denoise_s = 1e30;
    for (int seed = 1; seed <= 2; ++seed) {
      RenderSettings s = plain;
      s.seed = std::uint64_t(seed), s.samples = AdaptiveBudget{spp, spp / 4};
      auto start = std::chrono::steady_clock::now();
      const RenderResult a = render(scene, s);
      alone_s = std::min(alone_s, seconds_since(start));
      alone += ref.image_error(a.film.pixels()) / 2;
      s = denoise_settings(width, height, spp, std::uint64_t(seed));
      s.samples = AdaptiveBudget{spp, spp / 4};
      start = std::chrono::steady_clock::now();
      const RenderResult r = render(scene, s);
      render_s = std::min(render_s, seconds_since(start));
      const DenoisedImage d = denoise(denoise_input(r));
      denoise_s = std::min(denoise_s, d.seconds);
      denoised += ref.image_error(d.image.pixels()) / 2;
    }
    std::printf(
        "  --adaptive %3d spp: true error %.5f in %.3f s | --denoise: true error %.5f, render "
        "%.3f s + denoise %.3f s = %.3f s\n",
        spp, alone, alone_s, denoised, render_s, denoise_s, render_s + denoise_s);
    adaptive_curve.push_back({spp, alone, alone_s});
    adaptive_denoised_curve.push_back({spp, denoised, render_s + denoise_s});
  }
  std::printf("  the default image's error, %.5f, %.3f s: how soon each reaches it\n", error,
              fastest);
  print_crossing("--denoise", denoised_curve, error, fastest);
  print_crossing("--adaptive", adaptive_curve, error, fastest);
  print_crossing("--adaptive --denoise", adaptive_denoised_curve, error, fastest);
}

// --image-error E --denoise: the error each render delivers against the reference, as a
// fraction of E, and what the render and its judgements cost.
void target(const Scene& scene, int width, int height, int reference_spp, int seeds,
            const std::vector<double>& errors) {
  const Reference ref = reference_of(scene, width, height, reference_spp);
  for (const double e : errors) {
    for (int seed = 1; seed <= seeds; ++seed) {
      RenderSettings s = denoise_settings(width, height, 0, std::uint64_t(seed));
      s.samples = ImageErrorTarget{e, kDefaultErrorDrivenMaxSpp, kDefaultLeastSamples, true};
      RenderProgress progress;
      const RenderResult r = render(scene, s, &progress);
      const double truth = ref.image_error(r.denoised->image.pixels());
      std::printf(
          "%s %dx%d image error %.3f denoised seed %d: %u spp, %d judgements, estimated %.5f, "
          "true %.5f = %.3f E | %.2f s\n",
          scene.name.c_str(), width, height, e, seed, r.pixel_samples.front(),
          int(progress.judgements.load()), r.estimated_image_error, truth, truth / e,
          r.render_seconds);
    }
  }
}

}  // namespace
}  // namespace rtiow

int main(int argc, char** argv) {
  using namespace rtiow;
  const std::string mode = argc > 1 ? argv[1] : "";
  const bool calibration = mode == "calibrate" || mode == "calibrate-adaptive";
  if ((!calibration || argc < 7) && (mode != "trade" || argc != 5) &&
      (mode != "target" || argc < 7)) {
    std::fprintf(stderr,
                 "usage: %s calibrate[-adaptive] SCENE WIDTH REFERENCE_SPP SEEDS SPP...\n"
                 "       %s trade SCENE WIDTH REFERENCE_SPP\n"
                 "       %s target SCENE WIDTH REFERENCE_SPP SEEDS ERROR...\n",
                 argv[0], argv[0], argv[0]);
    return 2;
  }
  try {
    const Scene scene = make_builtin_scene(argv[2], kDefaultSceneSeed);
    const int width = std::stoi(argv[3]), reference_spp = std::stoi(argv[4]);
    if (mode == "trade") {  // the height as the command line rounds it
      trade(scene, width, int(std::lround(width / scene.image.aspect_ratio)), reference_spp);
      return 0;
    }
    const int height = int(width / scene.image.aspect_ratio);  // truncated, as the study ran
    if (mode == "target") {
      std::vector<double> errors;
      for (int i = 6; i < argc; ++i) errors.push_back(std::stod(argv[i]));
      target(scene, width, height, reference_spp, std::stoi(argv[5]), errors);
      return 0;
    }
    std::vector<int> counts;
    for (int i = 6; i < argc; ++i) counts.push_back(std::stoi(argv[i]));
    if (mode == "calibrate-adaptive" &&
        std::any_of(counts.begin(), counts.end(), [](int n) { return n <= kDefaultLeastSamples; }))
      throw std::invalid_argument("an adaptive budget must be above the minimum of " +
                                  std::to_string(kDefaultLeastSamples) + " spp");
    calibrate(scene, width, height, reference_spp, std::stoi(argv[5]), counts,
              mode == "calibrate-adaptive");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rtiow_denoise_study: %s\n", e.what());
    return 1;
  }
  return 0;
}
