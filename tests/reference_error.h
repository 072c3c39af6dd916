#pragma once
// The true error of an image against an independent reference render, as rtiow's image error
// counts it (relative to the reference, offset 0.01), with the reference's own variance (from
// its two halves) taken out: what the denoiser's reported error is tested against.

#include <cstddef>
#include <vector>

#include "core/denoise/denoise_input.h"
#include "core/denoise/denoiser.h"

namespace rtiow {

// Summed over the pixels [x0, x1) x [y0, y1) and their channels.
inline double true_relative_squared_error(const DenoiseInput& reference,
                                          const std::vector<Color>& image, int x0, int y0, int x1,
                                          int y1) {
  double total = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const std::size_t p = std::size_t(y) * std::size_t(reference.width) + std::size_t(x);
      for (std::size_t c = 0; c < 3; ++c) {
        const double r = reference.mean[p][c], level = (r + 0.01) * (r + 0.01);
        const double halves = double(reference.even[p][c]) - double(reference.odd[p][c]);
        const double e = double(image[p][c]) - r;
        total += (e * e - halves * halves / 4) / level;  // less the reference's own variance
      }
    }
  }
  return total;
}

// Summed over the whole image; divide by 3 x pixels for the mean.
inline double true_relative_squared_error(const DenoiseInput& reference,
                                          const std::vector<Color>& image) {
  return true_relative_squared_error(reference, image, 0, 0, reference.width, reference.height);
}

// The denoiser's per-pixel error channel summed over the pixels [x0, x1) x [y0, y1) and their
// channels, read relative to the denoised image (offset 0.01) as a user of the file reads it.
inline double channel_relative_squared_error(const DenoisedImage& d, int x0, int y0, int x1,
                                             int y1) {
  double total = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const std::size_t p = std::size_t(y) * std::size_t(d.image.width()) + std::size_t(x);
      for (std::size_t c = 0; c < 3; ++c) {
        const double z = d.image.pixels()[p][c];
        total += d.mse[p][c] / ((z + 0.01) * (z + 0.01));
      }
    }
  }
  return total;
}

}  // namespace rtiow
