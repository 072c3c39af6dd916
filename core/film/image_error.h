#pragma once
// How far a rendered image is from a reference, with the noise of both taken out where it
// would otherwise be counted as error. Each image carries the variance of each pixel's
// mean (per channel), estimated from its own samples (core/film/pixel_variance.h).

#include <vector>

#include "core/film/film.h"
#include "core/geometry/vec3.h"

namespace rtiow {

struct ImageEstimate {
  Film film;
  std::vector<Vec3d> variance;  // of each pixel's mean; empty when unknown (taken as 0)
};

struct ImageError {
  // Root mean squared error over pixels and channels, less the reference's own variance
  // (an independent reference adds its variance to the expected squared error).
  double rmse = 0.0;
  // pbrt-v4's relMSE: the mean of (v - ref)^2 / (ref + 0.01)^2, corrected the same way.
  double rel_mse = 0.0;
  // The signed relative difference of the image sums, (sum v - sum ref) / sum ref, and its
  // standard error from both images' variances: a bias shows as |difference| >> error. One
  // path gives a pixel all three channels, so they are correlated and the variance of their
  // sum is not the sum of theirs: it is taken at its bound, (sum of their deviations)^2, which
  // an image of grey-ish paths nearly reaches (the sum of the three variances made the cover's
  // z-scores spread 1.9-2.0 over seeds where 1 is honest; with the bound 1.1-1.2).
  double mean_difference = 0.0;
  double mean_difference_error = 0.0;
  // sqrt of the mean of (v - ref)^2 - var(v) - var(ref): the per-pixel bias with both
  // images' noise taken out (0 when the noise explains all of the difference).
  double rms_bias = 0.0;
  double rms_noise = 0.0;  // sqrt of the mean variance of the image's pixels
};

// Throws std::invalid_argument when the sizes differ.
ImageError measure_error(const ImageEstimate& image, const ImageEstimate& reference);

}  // namespace rtiow
