#include "core/compare/diff_images.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace rtiow {

Film difference_image(const DiffInput& test, const DiffInput& reference) {
  Film film(test.width, test.height);
  float largest = 1e-12f;
  for (std::size_t i = 0; i < test.rgb.size(); ++i) {
    const float e = std::abs(test.rgb[i] - reference.rgb[i]);
    if (std::isfinite(e)) largest = std::max(largest, e);
  }
  for (int y = 0; y < test.height; ++y) {
    for (int x = 0; x < test.width; ++x) {
      const std::size_t p = 3 * (std::size_t(y) * std::size_t(test.width) + std::size_t(x));
      const auto scaled = [&](std::size_t c) {
        const float e = std::abs(test.rgb[p + c] - reference.rgb[p + c]) / largest;
        return std::isfinite(e) ? e : 1.0f;  // NaN and infinities show as white
      };
      film.at(x, y) = {scaled(0), scaled(1), scaled(2)};
    }
  }
  return film;
}

Film z_image(const NoiseDiff& d, int width, int height) {
  Film film(width, height);
  const int per_row = (width + d.block_size - 1) / d.block_size;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float z = d.block_z[std::size_t((y / d.block_size) * per_row + x / d.block_size)];
      const float level = std::min(1.0f, std::abs(z) / float(d.block_critical_z));
      const float grey = 0.1f * (1.0f - level);
      film.at(x, y) = z > 0 ? Color{grey + level, grey, grey} : Color{grey, grey, grey + level};
    }
  }
  return film;
}

Film to_film(const DiffInput& image) {
  Film film(image.width, image.height);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const std::size_t p = 3 * (std::size_t(y) * std::size_t(image.width) + std::size_t(x));
      const auto value = [&](std::size_t c) {
        const float v = image.rgb[p + c];
        return image.linear ? v : v * v;
      };
      film.at(x, y) = {value(0), value(1), value(2)};
    }
  }
  return film;
}

}  // namespace rtiow
