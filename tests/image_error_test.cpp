// measure_error: known differences come out as known numbers, and the references' noise
// is taken out of the error rather than counted in it.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/film/image_error.h"

namespace rtiow {
namespace {

ImageEstimate flat(int w, int h, float value, double variance = 0.0) {
  ImageEstimate e{Film(w, h), {}};
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) e.film.at(x, y) = {value, value, value};
  }
  if (variance > 0) e.variance.assign(std::size_t(w * h), Vec3d{variance, variance, variance});
  return e;
}

TEST(ImageError, IdenticalImagesHaveNoError) {
  const ImageError e = measure_error(flat(4, 3, 0.5f), flat(4, 3, 0.5f));
  EXPECT_EQ(e.rmse, 0.0);
  EXPECT_EQ(e.rel_mse, 0.0);
  EXPECT_EQ(e.mean_difference, 0.0);
  EXPECT_EQ(e.rms_bias, 0.0);
}

TEST(ImageError, AConstantOffsetIsItsOwnRmseAndRelativeError) {
  const ImageError e = measure_error(flat(4, 3, 0.6f), flat(4, 3, 0.5f));
  EXPECT_NEAR(e.rmse, 0.1, 1e-6);
  EXPECT_NEAR(e.rel_mse, 0.01 / (0.51 * 0.51), 1e-6);
  EXPECT_NEAR(e.mean_difference, 0.2, 1e-6);
  EXPECT_NEAR(e.rms_bias, 0.1, 1e-6);
}

TEST(ImageError, TheReferencesNoiseIsTakenOut) {
  // A difference of 0.1 that the two images' variances (0.004 + 0.006) fully explain.
  const ImageError e = measure_error(flat(2, 2, 0.6f, 0.004), flat(2, 2, 0.5f, 0.006));
  EXPECT_NEAR(e.rmse, std::sqrt(0.01 - 0.006), 1e-6);
  EXPECT_NEAR(e.rms_bias, 0.0, 1e-4);
  EXPECT_NEAR(e.rms_noise, std::sqrt(0.004), 1e-9);
  // A pixel's three channels at their bound, fully correlated: 4 pixels of (3 * 0.1)^2.
  EXPECT_NEAR(e.mean_difference_error, std::sqrt(4 * 9 * 0.01) / (12 * 0.5), 1e-6);
}

TEST(ImageError, RefusesImagesOfDifferentSizes) {
  EXPECT_THROW(measure_error(flat(2, 2, 0.5f), flat(2, 3, 0.5f)), std::invalid_argument);
}

}  // namespace
}  // namespace rtiow
