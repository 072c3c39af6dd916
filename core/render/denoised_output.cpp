#include "core/render/denoised_output.h"

#include <cstdio>
#include <string>
#include <variant>

#include "core/denoise/denoiser.h"
#include "core/denoise/pixel_loop.h"
#include "core/film/replicate_variance.h"
#include "core/film/sample_sum.h"
#include "core/limits/error.h"
#include "core/limits/setting_name.h"
#include "core/render/render_metadata.h"
#include "core/render/render_settings.h"

namespace rtiow {

namespace {

// Why sums cannot be denoised, or empty.
std::string what_is_missing(const DenoiseSource& s) {
  if (s.replicates < kReplicates || !s.sums.keeps(SumGroup::Odd))
    return "the render kept one sequence of samples, not the two independent halves the "
           "denoiser compares";
  if (!s.sums.keeps(SumGroup::FirstHit))
    return "the render kept no first hits (albedo, normal, depth) for the denoiser to follow";
  if (s.samples.size() != s.sums.size() ||
      s.sums.size() != std::size_t(s.width) * std::size_t(s.height))
    return "the render has no sample counts";
  for (std::uint32_t n : s.samples) {
    if (odd_samples(s.first_sample, n) == 0 || n - odd_samples(s.first_sample, n) == 0)
      return "a pixel has fewer than one sample in each half (at least 2 spp are needed)";
  }
  return {};
}

DenoiseSource source_of(const RenderResult& r) {
  return {r.sums, r.pixel_samples, r.first_sample, r.replicates, r.film.width(), r.film.height()};
}

Color half_mean(const PixelSum& sum, std::uint64_t samples) {
  return sum.mean(samples);
}

}  // namespace

std::string why_not_denoised(const DenoiseSource& source) {
  return what_is_missing(source);
}

std::string why_not_denoised(const RenderResult& result) {
  return what_is_missing(source_of(result));
}

DenoiseInput denoise_input(const DenoiseSource& s) {
  if (const std::string missing = what_is_missing(s); !missing.empty())
    throw InvalidInput(setting("denoise") + ": " + missing);
  DenoiseInput in;
  in.width = s.width;
  in.height = s.height;
  const std::size_t n = s.sums.size();
  in.mean.resize(n), in.even.resize(n), in.odd.resize(n), in.features.resize(n);
  in.even_samples.resize(n), in.odd_samples.resize(n);
  // Every pixel's own: in parallel, the same bits.
  for_each_pixel(s.width, s.height, [&](std::size_t p) {
    const std::uint32_t samples = s.samples[p];
    in.mean[p] = s.sums.color[p].mean(samples);  // as the render's film resolves it
    const auto odd = std::uint32_t(odd_samples(s.first_sample, samples));
    const PixelSum& odd_sum = s.sums.spreads[p].odd;
    PixelSum even_sum;
    for (int c = 0; c < 3; ++c)
      even_sum.set_channel(c, s.sums.color[p].channel(c) - odd_sum.channel(c));
    in.even[p] = half_mean(even_sum, samples - odd);
    in.odd[p] = half_mean(odd_sum, odd);
    in.even_samples[p] = samples - odd;
    in.odd_samples[p] = odd;
    for (std::size_t c = 0; c < FirstHitSum::kChannels; ++c)
      in.features[p][c] = s.sums.first_hits[p].mean(c, samples);
  });
  return in;
}

DenoiseInput denoise_input(const RenderResult& r) {
  return denoise_input(source_of(r));
}

DenoiseFigures figures_of(const DenoisedImage& d) {
  return {d.estimated_error, d.noisy_error, d.seconds};
}

std::string describe(const DenoiseFigures& f) {
  char line[160];
  std::snprintf(
      line, sizeof line,
      "denoised in %.2f s: image error %.4f estimated (the noisy image %.4f by the same estimate)",
      f.seconds, f.estimated_error, f.noisy_error);
  return line;
}

void take_delivered_estimate(const RenderSettings& settings, RenderResult& result,
                             const DenoisedImage& denoised) {
  const auto* target = std::get_if<ImageErrorTarget>(&settings.samples);
  if (!target || !target->denoised) return;
  result.estimated_image_error = denoised.estimated_error;
  result.error_estimate = ErrorEstimate::Calibrated;
}

DenoisedImage denoised_image(const RenderResult& result, const DenoiseControl& control) {
  if (result.denoised) return *result.denoised;
  return denoise(denoise_input(result), control);
}

DenoisedOutput denoised_output(DenoisedImage d, bool extra_channels, Metadata& metadata) {
  DenoisedOutput out;
  out.figures = figures_of(d);
  metadata.emplace_back(metadata_key::kDenoisedError, d.estimated_error);
  metadata.emplace_back(metadata_key::kDenoisedNoisyError, d.noisy_error);
  if (extra_channels) {
    const std::size_t n = d.mse.size();
    const char* rgb[3] = {"R", "G", "B"};
    for (std::size_t c = 0; c < 3; ++c) {
      ExtraChannel noisy{std::string("noisy.") + rgb[c], std::vector<float>(n)};
      for (std::size_t p = 0; p < n; ++p) noisy.values[p] = d.noisy.pixels()[p][c];
      out.channels.push_back(std::move(noisy));
    }
    for (std::size_t c = 0; c < 3; ++c) {
      ExtraChannel mse{std::string("denoise.mse.") + rgb[c], std::vector<float>(n)};
      for (std::size_t p = 0; p < n; ++p) mse.values[p] = float(d.mse[p][c]);
      out.channels.push_back(std::move(mse));
    }
    out.channels.push_back({"denoise.kept", std::move(d.noisy_kept)});
  }
  out.image = std::move(d.image);
  return out;
}

}  // namespace rtiow
