#include "core/render/adaptive_sampling.h"

#include "core/film/pixel_variance.h"

namespace rtiow {

// The relative variance per sample a pixel is judged by: the mean of its neighbours' in
// the 3x3 window around it, itself left out. A rule that looked at the pixel's own samples
// would stop more often after lucky ones (a bright sample lowers the relative error, a
// missed rare path the variance) and bias the pixel; its neighbours' samples are
// independent of its own, so its mean stays unbiased. A 1x1 image has no neighbours and
// uses its own.
std::vector<double> neighbourhood_relative_variance(const RenderSettings& settings,
                                                    const PixelAccumulators& pixels) {
  const int w = settings.width, h = settings.height;
  std::vector<double> own(pixels.samples.size());
  for (std::size_t p = 0; p < own.size(); ++p) {
    own[p] = relative_sample_variance(pixels.sums[p], pixels.squares[p], pixels.samples[p]);
  }
  std::vector<double> judged(own.size());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double total = 0;
      int count = 0;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          total += own[std::size_t(ny) * std::size_t(w) + std::size_t(nx)];
          ++count;
        }
      }
      const std::size_t p = std::size_t(y) * std::size_t(w) + std::size_t(x);
      judged[p] = count > 0 ? total / count : own[p];
    }
  }
  return judged;
}

}  // namespace rtiow
