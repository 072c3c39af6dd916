#pragma once
// The rendered image: linear RGB per pixel, row 0 at the top.

#include <cstddef>
#include <vector>

#include "core/geometry/vec3.h"

namespace rtiow {

// Where a film lies in the frame the camera sees (a crop): film pixel (x, y) is frame pixel
// (x + this->x, y + this->y) of a frame_width x frame_height image. Sizes of 0: the film is
// the whole frame.
struct FramePlacement {
  int x = 0, y = 0;
  int frame_width = 0, frame_height = 0;
  bool whole() const { return frame_width == 0 && frame_height == 0; }
};

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
