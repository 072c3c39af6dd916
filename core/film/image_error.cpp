#include "core/film/image_error.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/film/pixel_variance.h"

namespace rtiow {

ImageError measure_error(const ImageEstimate& image, const ImageEstimate& reference) {
  const std::size_t pixels = image.film.pixels().size();
  if (image.film.width() != reference.film.width() ||
      image.film.height() != reference.film.height()) {
    throw std::invalid_argument("measure_error: the image and the reference differ in size");
  }
  const auto variance = [](const ImageEstimate& e, std::size_t p) {
    return e.variance.empty() ? Vec3d{0, 0, 0} : e.variance[p];
  };
  double squared_noise_free = 0, relative = 0, bias_squared = 0, noise = 0;
  double sum_image = 0, sum_reference = 0, sum_variance = 0;
  for (std::size_t p = 0; p < pixels; ++p) {
    const Color v = image.film.pixels()[p], r = reference.film.pixels()[p];
    const Vec3d var_v = variance(image, p), var_r = variance(reference, p);
    double deviation = 0;  // of the pixel's channel sum: see mean_difference_error
    for (std::size_t c = 0; c < 3; ++c) {
      const double d = double(v[c]) - double(r[c]);
      const double offset = double(r[c]) + kRelativeErrorOffset;
      squared_noise_free += d * d - var_r[c];
      relative += (d * d - var_r[c]) / (offset * offset);
      bias_squared += d * d - var_r[c] - var_v[c];
      noise += var_v[c];
      sum_image += v[c];
      sum_reference += r[c];
      deviation += std::sqrt(var_v[c] + var_r[c]);
    }
    sum_variance += deviation * deviation;
  }
  const double n = 3.0 * double(pixels);
  ImageError e;
  e.rmse = std::sqrt(std::max(0.0, squared_noise_free / n));
  e.rel_mse = std::max(0.0, relative / n);
  e.rms_bias = std::sqrt(std::max(0.0, bias_squared / n));
  e.rms_noise = std::sqrt(noise / n);
  if (sum_reference > 0) {
    e.mean_difference = (sum_image - sum_reference) / sum_reference;
    e.mean_difference_error = std::sqrt(sum_variance) / sum_reference;
  }
  return e;
}

}  // namespace rtiow
