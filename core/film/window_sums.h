#pragma once
// The sum of a per-pixel quantity over the square window around each pixel, clipped at the
// image's edges: what the replicate variances pool from a pixel's neighbours and what the
// denoiser's window means divide.

#include <algorithm>
#include <cstddef>
#include <vector>

#include "core/parallel/parallel_for_range.h"

namespace rtiow {

// Rows (or columns) of pixels one task of the passes below takes.
inline constexpr std::size_t kWindowRowsPerTask = 16, kWindowColumnsPerTask = 64;

// The sums of `values` (row major, width x height) over the (2 r + 1)^2 window around each
// pixel, clipped at the edges, into `sums`; `table` is working space (both are resized, and
// keep their memory from call to call). Summed-area table: each row's running sums, then each
// column's running sum of those down the rows, then the windows, each step in parallel over
// rows or columns and each sum in one order: the same bits for any thread count.
template <typename T>
void window_sums(const std::vector<T>& values, int width, int height, int r, std::vector<T>& table,
                 std::vector<T>& sums) {
  const auto w = std::size_t(width) + 1, rows = std::size_t(height);
  table.resize(w * (rows + 1));
  std::fill_n(table.begin(), w, T{});  // the row above the image
  parallel_for_range(rows, kWindowRowsPerTask, [&](std::size_t y0, std::size_t y1) {
    for (std::size_t y = y0; y < y1; ++y) {
      T row{};
      table[(y + 1) * w] = T{};  // the column left of the image
      for (std::size_t x = 0; x < std::size_t(width); ++x) {
        row = row + values[y * std::size_t(width) + x];
        table[(y + 1) * w + x + 1] = row;
      }
    }
  });
  parallel_for_range(
      std::size_t(width), kWindowColumnsPerTask, [&](std::size_t x0, std::size_t x1) {
        for (std::size_t y = 1; y < rows; ++y)
          for (std::size_t x = x0; x < x1; ++x)
            table[(y + 1) * w + x + 1] = table[y * w + x + 1] + table[(y + 1) * w + x + 1];
      });
  sums.resize(values.size());
  parallel_for_range(rows, kWindowRowsPerTask, [&](std::size_t first_row, std::size_t end_row) {
    for (int y = int(first_row); y < int(end_row); ++y) {
      const auto y0 = std::size_t(std::max(0, y - r)),
                 y1 = std::size_t(std::min(height, y + r + 1));
      for (int x = 0; x < width; ++x) {
        const auto x0 = std::size_t(std::max(0, x - r)),
                   x1 = std::size_t(std::min(width, x + r + 1));
        sums[std::size_t(y) * std::size_t(width) + std::size_t(x)] =
            table[y1 * w + x1] - table[y0 * w + x1] - table[y1 * w + x0] + table[y0 * w + x0];
      }
    }
  });
}

// The same, returned.
template <typename T>
std::vector<T> window_sums(const std::vector<T>& values, int width, int height, int r) {
  std::vector<T> table, sums;
  window_sums(values, width, height, r, table, sums);
  return sums;
}

// The number of pixels in the window around (x, y), clipped as window_sums() clips it.
inline double window_pixels(int width, int height, int r, int x, int y) {
  const int x0 = std::max(0, x - r), x1 = std::min(width, x + r + 1);
  const int y0 = std::max(0, y - r), y1 = std::min(height, y + r + 1);
  return double((x1 - x0) * (y1 - y0));
}

}  // namespace rtiow
