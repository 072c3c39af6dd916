#pragma once
// The mean of a per-pixel quantity over the square window around each pixel: how the denoiser
// pools what one pixel cannot tell alone (the guides' noise level, a neighbourhood's error
// estimates, the per-pixel error channel).

#include <algorithm>
#include <cstddef>
#include <vector>

#include "core/denoise/pixel_loop.h"
#include "core/parallel/parallel_for_range.h"

namespace rtiow {

// The mean of `values` (row major, width x height) over the (2 r + 1)^2 window around each
// pixel, clipped at the edges, with the pixel itself left out when `leave_out`. Summed-area
// table: each row's running sums, then each column's running sum of those down the rows, then
// the windows, each step in parallel over rows or columns and each sum in one order: the same
// bits for any thread count.
template <typename T>
std::vector<T> window_mean(const std::vector<T>& values, int width, int height, int r,
                           bool leave_out) {
  const auto w = std::size_t(width) + 1, rows = std::size_t(height);
  std::vector<T> table(w * (rows + 1), T{});
  parallel_for_range(rows, kPixelRowsPerTask, [&](std::size_t y0, std::size_t y1) {
    for (std::size_t y = y0; y < y1; ++y) {
      T row{};
      for (std::size_t x = 0; x < std::size_t(width); ++x) {
        row = row + values[y * std::size_t(width) + x];
        table[(y + 1) * w + x + 1] = row;
      }
    }
  });
  parallel_for_range(std::size_t(width), 64, [&](std::size_t x0, std::size_t x1) {
    for (std::size_t y = 1; y < rows; ++y)
      for (std::size_t x = x0; x < x1; ++x)
        table[(y + 1) * w + x + 1] = table[y * w + x + 1] + table[(y + 1) * w + x + 1];
  });
  std::vector<T> mean(values.size());
  parallel_for_range(rows, kPixelRowsPerTask, [&](std::size_t first_row, std::size_t end_row) {
    for (int y = int(first_row); y < int(end_row); ++y) {
      for (int x = 0; x < width; ++x) {
        const auto x0 = std::size_t(std::max(0, x - r)),
                   x1 = std::size_t(std::min(width, x + r + 1));
        const auto y0 = std::size_t(std::max(0, y - r)),
                   y1 = std::size_t(std::min(height, y + r + 1));
        const std::size_t p = std::size_t(y) * std::size_t(width) + std::size_t(x);
        T sum = table[y1 * w + x1] - table[y0 * w + x1] - table[y1 * w + x0] + table[y0 * w + x0];
        double count = double((x1 - x0) * (y1 - y0));
        if (leave_out && count > 1) sum = sum - values[p], count -= 1;
        mean[p] = sum * (1.0 / count);
      }
    }
  });
  return mean;
}

}  // namespace rtiow
