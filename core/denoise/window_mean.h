#pragma once
// The mean of a per-pixel quantity over the square window around each pixel: how the denoiser
// pools what one pixel cannot tell alone (the guides' noise level, a neighbourhood's error
// estimates, the per-pixel error channel).

#include <cstddef>
#include <vector>

#include "core/denoise/pixel_loop.h"
#include "core/film/window_sums.h"

namespace rtiow {

// The mean of `values` (row major, width x height) over the (2 r + 1)^2 window around each
// pixel, clipped at the edges, with the pixel itself left out when `leave_out`; the same bits
// for any thread count.
template <typename T>
std::vector<T> window_mean(const std::vector<T>& values, int width, int height, int r,
                           bool leave_out) {
  std::vector<T> mean = window_sums(values, width, height, r);
  for_each_pixel(width, height, [&](std::size_t p) {
    const int x = int(p % std::size_t(width)), y = int(p / std::size_t(width));
    double count = window_pixels(width, height, r, x, y);
    if (leave_out && count > 1) mean[p] = mean[p] - values[p], count -= 1;
    mean[p] = mean[p] * (1.0 / count);
  });
  return mean;
}

}  // namespace rtiow
