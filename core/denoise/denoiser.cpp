#include "core/denoise/denoiser.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "core/denoise/candidate_blend.h"
#include "core/denoise/equal_weight_regression.h"
#include "core/denoise/feature_regression.h"
#include "core/denoise/pixel_loop.h"
#include "core/denoise/window_mean.h"
#include "core/film/pixel_variance.h"

namespace rtiow {

namespace {

// What a pixel of each pass costs, for the progress a display shows (measured at 1600x1067 on 2
// cores: the first pass 1.07 s, each half's second pass 2.38 s, the blend 0.43 s).
constexpr std::uint64_t kFirstPassWork = 8, kSecondPassWork = 20, kBlendChannelWork = 1;
constexpr std::uint64_t kWorkPerPixel =
    kFirstPassWork + 2 * kSecondPassWork + 3 * kBlendChannelWork;

// The per-sample variance that weights the patches is the replicate estimate, one degree of
// freedom a pixel, averaged over (2 r + 1)^2 pixels.
constexpr int kNoiseLevelRadius = 2;
// A pixel's blend of the candidates is chosen by their estimated error summed over (2 r + 1)^2
// pixels (the pixel left out): at 200 and 400 pixels wide, 15x15 gave up to 37% less squared error
// than choosing by 7x7 and more than 5x5 or 11x11; 21x21 about the same (docs/denoising.md).
constexpr int kBlendRadius = 7;
// The per-pixel error channel is the estimate averaged over (2 r + 1)^2 pixels.
constexpr int kErrorChannelRadius = 3;

// The second pass's two filters: a regression at bandwidth 0.5 (NFOR's sharper one) and a
// weighted mean at bandwidth 2. The mean in place of NFOR's regression at bandwidth 1, measured
// 2026-11-30 at 200 and 400 pixels wide, 8 and 32 spp (docs/denoising.md): 9% more squared error
// gain in the geometric mean (up to 31%), the lowest estimate over true error 0.83 instead of
// 0.65, and no normal matrix to gather. A mean at bandwidth 1 gained less, at 3 over-read.
constexpr std::array<Weighting, 2> kWeightings{Weighting{0.5f, Fit::kRegression},
                                               Weighting{2.0f, Fit::kMean}};

// The halves' filtered means combined as the noisy mean combines them (weighted by their
// counts), never below 0, and each pixel's own weight in it: d combined(p) / d noisy(p) is
// (n_even h_even + n_odd h_odd) / n for halves of equal per-sample variance.
struct Combined {
  std::vector<Color> color;
  std::vector<float> own_weight;
};

Combined combine(const DenoiseInput& in, const FilteredHalf& even, const FilteredHalf& odd) {
  Combined out;
  out.color.resize(in.size()), out.own_weight.resize(in.size());
  for_each_pixel(in.width, in.height, [&](std::size_t p) {
    const double ne = in.even_samples[p], no = in.odd_samples[p], total = ne + no;
    for (std::size_t c = 0; c < 3; ++c) {
      const double v = (ne * double(even.color[p][c]) + no * double(odd.color[p][c])) / total;
      out.color[p][c] = float(std::max(0.0, v));
    }
    out.own_weight[p] =
        float((ne * double(even.own_weight[p]) + no * double(odd.own_weight[p])) / total);
  });
  return out;
}

// The noisy mean's variance at each pixel, from the halves: unbiased, one degree of freedom
// per channel, whatever the sampler.
std::vector<Vec3d> noisy_variance(const DenoiseInput& in) {
  std::vector<Vec3d> variance(in.size());
  for_each_pixel(in.width, in.height, [&](std::size_t p) {
    const double ne = in.even_samples[p], no = in.odd_samples[p], total = ne + no;
    const Vec3d diff = Vec3d(in.even[p]) - Vec3d(in.odd[p]);
    variance[p] = diff * diff * (ne * no / (total * total));
  });
  return variance;
}

// The two passes (core/denoise/feature_regression.h): the second pass's image with each
// weighting. `variance` is the noisy mean's.
std::vector<Combined> second_pass_images(const DenoiseInput& in, const std::vector<Vec3d>& variance,
                                         const DenoiseControl& control) {
  // Each pass's rows stop once `control` is stopped; what they left is thrown away here.
  const auto filter = [&](const std::vector<Color>& half, const Guide& guide,
                          const std::vector<Weighting>& weightings) {
    std::vector<FilteredHalf> out =
        filter_half(in, half, guide, weightings, control.pass(kSecondPassWork));
    if (control.stop()) throw DenoiseCancelled();
    return out;
  };
  const std::size_t n = in.size();
  // The per-sample variance, the guides' noise level, pooled over a window.
  std::vector<Vec3d> sample_variance(n);
  for_each_pixel(in.width, in.height, [&](std::size_t p) {
    sample_variance[p] = variance[p] * double(in.even_samples[p] + in.odd_samples[p]);
  });
  sample_variance = window_mean(sample_variance, in.width, in.height, kNoiseLevelRadius, false);
  // First pass: each half regressed on the features with its neighbours weighted equally; a
  // function of that half's samples alone. The same weights and design: fitted together.
  std::vector<FilteredHalf> first =
      regress_equally(in, {&in.even, &in.odd}, control.pass(kFirstPassWork));
  if (control.stop()) throw DenoiseCancelled();
  const FilteredHalf first_even = std::move(first[0]);
  const FilteredHalf first_odd = std::move(first[1]);
  // Second pass: each half weighted by the patches of the other's first pass, whose noise is
  // about its own weight times the half's (a regression's hat rows have squares summing to it).
  const auto guide_variance = [&](const FilteredHalf& f, const std::vector<std::uint32_t>& count) {
    std::vector<Vec3d> v(n);
    for_each_pixel(in.width, in.height, [&](std::size_t p) {
      v[p] = sample_variance[p] * (double(f.own_weight[p]) / double(count[p]));
    });
    return v;
  };
  const std::vector<Vec3d> odd_guide_variance = guide_variance(first_odd, in.odd_samples);
  const std::vector<Vec3d> even_guide_variance = guide_variance(first_even, in.even_samples);
  const std::vector<Weighting> weightings(kWeightings.begin(), kWeightings.end());
  const auto second_even = filter(in.even, {&first_odd.color, &odd_guide_variance}, weightings);
  const auto second_odd = filter(in.odd, {&first_even.color, &even_guide_variance}, weightings);
  std::vector<Combined> images;
  for (std::size_t k = 0; k < weightings.size(); ++k)
    images.push_back(combine(in, second_even[k], second_odd[k]));
  return images;
}

// The relative error's denominators, (level + 0.01)^2: the sharper second-pass image at the
// pixel, or the mean of its 8 neighbours where that is lower. Whatever of the pixel's own noise
// is in its level divides its own error (a bright outlier in a dark region): the noisy value
// reported 0.71 of the noisy image's true error on the materials scene at 8 spp; the filtered
// value alone, which keeps some of it, 0.65-0.90 of the denoised error there at 16 spp and 96
// pixels wide, this 0.70-0.96; a 3x3 mean alone, blurred across edges, 0.87 on the cover.
// Returned as 1 / (level + 0.01)^2 a pixel and channel: what its squared error is multiplied by.
std::vector<Vec3d> relative_weights(const DenoiseInput& in, const std::vector<Color>& sharper) {
  const std::vector<Vec3d> level(sharper.begin(), sharper.end());
  const std::vector<Vec3d> around = window_mean(level, in.width, in.height, 1, true);
  std::vector<Vec3d> weight(level.size());
  for_each_pixel(in.width, in.height, [&](std::size_t p) {
    for (std::size_t c = 0; c < 3; ++c) {
      const double d = std::min(level[p][c], around[p][c]) + kRelativeErrorOffset;
      weight[p][c] = 1.0 / (d * d);
    }
  });
  return weight;
}

// A squared error, relative, summed over the channels.
double relative_sum(const Vec3d& squared_error, const Vec3d& weight) {
  return squared_error.x * weight.x + squared_error.y * weight.y + squared_error.z * weight.z;
}

// Each pixel's estimated squared error for the channel a file keeps: the pixels' own estimates
// are noise about their errors (one degree of freedom a pixel, often below 0), so they are
// averaged over a window, and averaged relative to each pixel's level, as the image's error is
// measured. Averaged as they are, a bright pixel's squared error landed on its dark neighbours,
// whose level multiplies it by up to 10^4: read against the image, that channel summed to 3-42
// times the true error of the 2048-spp study's renders (docs/denoising.md); this one to 0.6-1.8.
std::vector<Vec3d> error_channel(const DenoiseInput& in, const std::vector<Vec3d>& error,
                                 const std::vector<Vec3d>& relative_weight) {
  std::vector<Vec3d> relative(error.size());
  for_each_pixel(in.width, in.height,
                 [&](std::size_t p) { relative[p] = error[p] * relative_weight[p]; });
  std::vector<Vec3d> channel =
      window_mean(relative, in.width, in.height, kErrorChannelRadius, false);
  for_each_pixel(in.width, in.height, [&](std::size_t p) {
    for (std::size_t c = 0; c < 3; ++c)
      channel[p][c] = std::max(0.0, channel[p][c]) / relative_weight[p][c];
  });
  return channel;
}

}  // namespace

DenoisedImage denoise(const DenoiseInput& in, const DenoiseControl& control) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n = in.size();
  if (control.progress) control.progress->begin(std::uint64_t(n) * kWorkPerPixel);
  const std::vector<Vec3d> variance = noisy_variance(in);
  const std::vector<Combined> filtered = second_pass_images(in, variance, control);
  const std::vector<Vec3d> relative_weight = relative_weights(in, filtered.front().color);
  BlendedImage blended =
      blend_candidates(in,
                       {FilteredCandidate{&filtered[0].color, &filtered[0].own_weight},
                        FilteredCandidate{&filtered[1].color, &filtered[1].own_weight}},
                       variance, relative_weight, kBlendRadius, control.pass(kBlendChannelWork));

  DenoisedImage out;
  out.image = Film(in.width, in.height);
  out.noisy = Film(in.width, in.height);
  out.noisy_kept = std::move(blended.noisy_share);
  double relative = 0.0, noisy_relative = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    const int x = int(p % std::size_t(in.width)), y = int(p / std::size_t(in.width));
    out.image.at(x, y) = blended.color[p];
    out.noisy.at(x, y) = in.mean[p];
    relative += relative_sum(blended.error[p], relative_weight[p]);
    noisy_relative += relative_sum(variance[p], relative_weight[p]);
  }
  out.mse = error_channel(in, blended.error, relative_weight);
  const double values = 3.0 * double(std::max<std::size_t>(n, 1));
  out.estimated_error = std::sqrt(std::max(0.0, relative / values));
  out.noisy_error = std::sqrt(std::max(0.0, noisy_relative / values));
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace rtiow
