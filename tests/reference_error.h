#pragma once
// The true error of an image against an independent reference render, as rtiow's image error
// counts it (relative to the reference, offset 0.01), with the reference's own variance (from
// its two halves) taken out: what the denoiser's reported error is tested against.

#include <cstddef>
#include <vector>

#include "core/denoise/denoise_input.h"

namespace rtiow {

// Summed over the pixels and their channels; divide by 3 x pixels for the mean.
inline double true_relative_squared_error(const DenoiseInput& reference,
                                          const std::vector<Color>& image) {
  double total = 0;
  for (std::size_t p = 0; p < reference.size(); ++p) {
    for (std::size_t c = 0; c < 3; ++c) {
      const double r = reference.mean[p][c], level = (r + 0.01) * (r + 0.01);
      const double halves = double(reference.even[p][c]) - double(reference.odd[p][c]);
      const double e = double(image[p][c]) - r;
      total += (e * e - halves * halves / 4) / level;  // less the reference's own variance
    }
  }
  return total;
}

}  // namespace rtiow
