#pragma once
// The mean of a per-pixel quantity over the square window around each pixel: how the denoiser
// pools what one pixel cannot tell alone (the guides' noise level, a neighbourhood's error
// estimates, the per-pixel error channel).

#include <algorithm>
#include <cstddef>
#include <vector>

namespace rtiow {

// The mean of `values` (row major, width x height) over the (2 r + 1)^2 window around each
// pixel, clipped at the edges, with the pixel itself left out when `leave_out`. Summed-area
// table, serial: the same bits for any thread count.
template <typename T>
std::vector<T> window_mean(const std::vector<T>& values, int width, int height, int r,
                           bool leave_out) {
  const auto w = std::size_t(width) + 1;
  std::vector<T> table(w * (std::size_t(height) + 1), T{});
  for (int y = 0; y < height; ++y) {
    T row{};
    for (int x = 0; x < width; ++x) {
      row = row + values[std::size_t(y) * std::size_t(width) + std::size_t(x)];
      table[(std::size_t(y) + 1) * w + std::size_t(x) + 1] =
          table[std::size_t(y) * w + std::size_t(x) + 1] + row;
    }
  }
  std::vector<T> mean(values.size());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const auto x0 = std::size_t(std::max(0, x - r)), x1 = std::size_t(std::min(width, x + r + 1));
      const auto y0 = std::size_t(std::max(0, y - r)),
                 y1 = std::size_t(std::min(height, y + r + 1));
      const std::size_t p = std::size_t(y) * std::size_t(width) + std::size_t(x);
      T sum = table[y1 * w + x1] - table[y0 * w + x1] - table[y1 * w + x0] + table[y0 * w + x0];
      double count = double((x1 - x0) * (y1 - y0));
      if (leave_out && count > 1) sum = sum - values[p], count -= 1;
      mean[p] = sum * (1.0 / count);
    }
  }
  return mean;
}

}  // namespace rtiow
