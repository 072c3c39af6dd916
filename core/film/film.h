#pragma once
// The rendered image: linear RGB per pixel, row 0 at the top.

#include <cstddef>
#include <vector>

#include "core/geometry/vec3.h"

namespace rtiow {

class Film {
 public:
  Film() = default;
  Film(int width, int height)
      : width_(width), height_(height), pixels_(std::size_t(width) * std::size_t(height)) {}

  int width() const { return width_; }
  int height() const { return height_; }
  Color& at(int x, int y) { return pixels_[std::size_t(y) * std::size_t(width_) + std::size_t(x)]; }
  const Color& at(int x, int y) const {
    return pixels_[std::size_t(y) * std::size_t(width_) + std::size_t(x)];
  }
  const std::vector<Color>& pixels() const { return pixels_; }

 private:
  int width_ = 0, height_ = 0;
  std::vector<Color> pixels_;
};

}  // namespace rtiow
