#pragma once
// A pixel's 3x3 neighbours, itself left out and the image's edges respected: what every
// per-pixel judgement pooled from neighbours walks (the replicate ratio's noise level in
// core/film/replicate_variance.cpp, adaptive sampling's pooled estimates in
// core/render/sample_allocation.cpp).

#include <cstddef>

namespace rtiow {

// Calls f(index) for each neighbour of (x, y) in a width x height row-major image.
template <typename F>
void for_each_neighbour(int width, int height, int x, int y, const F& f) {
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = x + dx, ny = y + dy;
      if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
      f(std::size_t(ny) * std::size_t(width) + std::size_t(nx));
    }
  }
}

}  // namespace rtiow
