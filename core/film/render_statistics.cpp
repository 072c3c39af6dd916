#include "core/film/render_statistics.h"

namespace rtiow {

std::vector<Vec3d> pixel_mean_variances(const RenderResult& result) {
  std::vector<Vec3d> variances;
  variances.reserve(result.sums.size());
  for (std::size_t p = 0; p < result.sums.size(); ++p) {
    variances.push_back(
        variance_of_mean(result.sums[p], result.squares[p], result.pixel_samples[p]));
  }
  return variances;
}

ImageEstimate to_estimate(const RenderResult& result) {
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

double mean_samples(const RenderResult& result) {
  double total = 0;
  for (const std::uint32_t n : result.pixel_samples) total += n;
  return result.pixel_samples.empty() ? 0.0 : total / double(result.pixel_samples.size());
}

}  // namespace rtiow
