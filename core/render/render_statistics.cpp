#include "core/render/render_statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <new>
#include <stdexcept>

#include "core/film/replicate_variance.h"

#include "core/io/image_backend.h"
#include "core/io/image_file.h"
#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/limits/setting_name.h"
#include "core/parallel/thread_count.h"
#include "core/render/sample_allocation.h"

namespace rtiow {

std::vector<Vec3d> pixel_mean_variances(const RenderResult& result) {
  if (result.replicates < kReplicates) {
    throw std::invalid_argument(
        "no estimate of the error of a render drawn from one sequence: render it with " +
        setting("stats_channels") + " (RenderSettings::estimate_error) to keep two replicates");
  }
  if (result.replicate_ratios && result.replicate_ratios->size() == result.pixel_samples.size()) {
    return honest_variances(*result.replicate_ratios, result.sums.color, result.sums.spreads,
                            result.pixel_samples, result.first_sample, result.sampler);
  }
  return honest_variances(result.film.width(), result.film.height(), result.sums.color,
                          result.sums.spreads, result.pixel_samples, result.first_sample,
                          result.sampler);
}

ImageEstimate to_estimate(const RenderResult& result) {
  // A render from one sequence has no estimate of its error: its variances are unknown.
  if (result.replicates < kReplicates) return {result.film, {}};
  return {result.film, pixel_mean_variances(result)};
}

std::vector<ExtraChannel> statistics_channels(const RenderResult& result) {
  std::vector<ExtraChannel> channels{
      {"spp", {}}, {"variance.R", {}}, {"variance.G", {}}, {"variance.B", {}}};
  const std::vector<Vec3d> variances = pixel_mean_variances(result);
  for (std::size_t p = 0; p < variances.size(); ++p) {
    channels[0].values.push_back(float(result.pixel_samples[p]));
    for (std::size_t c = 0; c < 3; ++c) channels[1 + c].values.push_back(float(variances[p][c]));
  }
  return channels;
}

std::optional<ImageEstimate> read_statistics_image(
    const std::string& path, int width, int height,
    const std::vector<std::pair<std::string, std::string>>& required) {
  constexpr int kChannels = 7;  // R, G, B, spp, variance.R, variance.G, variance.B
  std::error_code error;
  if (!std::filesystem::exists(std::filesystem::symlink_status(path, error))) return std::nullopt;
  // A cache is state rtiow continues: its own file, checked like every image it reads. One
  // that is not (another user's, a link, a crafted header) is not used, and is replaced.
  std::unique_ptr<ImageReader> in;
  try {
    in = open_input_image(path, "cached image " + quote_value(path), limits::kMaxPartFileBytes,
                          "cached image", InputKind::OwnState);
  } catch (const InvalidInput&) {
    return std::nullopt;
  }
  std::string reason;
  const ImageHeader& header = in->header();
  if (header.width != width || header.height != height ||
      header.channel_names.size() != kChannels) {
    return std::nullopt;
  }
  for (const auto& [key, value] : required) {
    if (header.string_attribute(kMetadataPrefix + key) != value) return std::nullopt;
  }
  std::vector<float> values(std::size_t(width) * std::size_t(height) * kChannels);
  if (!in->read_pixels(PixelType::Float, values.data(), reason)) return std::nullopt;
  ImageEstimate image{Film(width, height), {}};
  for (std::size_t p = 0; p < image.film.pixels().size(); ++p) {
    const float* v = &values[p * kChannels];
    image.film.at(int(p % std::size_t(width)), int(p / std::size_t(width))) = {v[0], v[1], v[2]};
    image.variance.push_back({v[4], v[5], v[6]});
  }
  return image;
}

std::vector<ExtraChannel> image_channels(const RenderResult& result, bool statistics,
                                         const FirstHitPasses& passes) {
  std::vector<ExtraChannel> channels;
  if (statistics) channels = statistics_channels(result);
  for (ExtraChannel& pass : pass_channels(result, passes)) channels.push_back(std::move(pass));
  return channels;
}

double mean_samples(const RenderResult& result) {
  double total = 0;
  for (const std::uint32_t n : result.pixel_samples) total += n;
  return result.pixel_samples.empty() ? 0.0 : total / double(result.pixel_samples.size());
}

ImageErrorEstimate estimate_image_error(const RenderResult& result, int threads) {
  const std::vector<std::uint32_t>& samples = result.pixel_samples;
  if (samples.empty() || result.sums.spreads.size() != samples.size() ||
      *std::min_element(samples.begin(), samples.end()) < 2) {
    return {};  // no spreads kept (parts of an older rtiow), or a pixel with too few samples
  }
  // What drew the samples, in the terms the pooled estimate takes.
  RenderSettings drawn;
  drawn.width = result.film.width();
  drawn.height = result.film.height();
  drawn.first_sample = result.first_sample;
  drawn.sampler = result.sampler;
  drawn.estimate_error = result.replicates >= kReplicates;
  double rel_mse = 0;
  std::shared_ptr<const std::vector<Vec3d>> ratios;
  try {
    rel_mse = with_threads(threads, [&] {
      auto r =
          std::make_shared<const std::vector<Vec3d>>(sampler_ratios(drawn, result.sums, samples));
      const double mean = estimated_rel_mse(
          neighbourhood_relative_variance(drawn, result.sums, samples, *r), samples);
      if (replicates(drawn) >= kReplicates) ratios = std::move(r);
      return mean;
    });
  } catch (const std::bad_alloc&) {
    return {};  // the pooled variances do not fit beside the render: no estimate, nothing lost
  }
  if (!std::isfinite(rel_mse)) return {};
  return {std::sqrt(rel_mse),
          replicates(drawn) >= kReplicates ? ErrorEstimate::Calibrated : ErrorEstimate::UpperBound,
          std::move(ratios)};
}

std::string to_string(ErrorEstimate kind) {
  switch (kind) {
    case ErrorEstimate::Calibrated:
      return "calibrated";
    case ErrorEstimate::UpperBound:
      return "upper bound";
    case ErrorEstimate::None:
      break;
  }
  return "none";
}

std::string describe_error_estimate(ErrorEstimate kind, double estimated) {
  char text[64] = "";
  if (kind == ErrorEstimate::Calibrated) {
    std::snprintf(text, sizeof text, "image error %.3g estimated", estimated);
  } else if (kind == ErrorEstimate::UpperBound) {
    std::snprintf(text, sizeof text, "image error at most %.3g", estimated);
  }
  return text;
}

std::string describe_error_estimate(const RenderResult& result) {
  return describe_error_estimate(result.error_estimate, result.estimated_image_error);
}

}  // namespace rtiow
