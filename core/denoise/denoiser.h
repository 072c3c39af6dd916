#pragma once
// The denoiser, and the error it delivers.
//
// Two passes of a feature regression (core/denoise/feature_regression.h), as NFOR filters
// twice: first each half of the samples with its neighbours weighted equally, then each half
// again with its neighbours weighted by the patches of the other half's first pass: regressed at
// bandwidth 0.5, and averaged (a weighted mean) at bandwidth 2. A half's filtered value so depends
// on the other half only through its weights, never through the pixel's own value: measured on the
// cover, weights from the other half's noisy mean gave 1.2x lower squared error but reported
// 0.65-0.77 of the error delivered at 8 spp, these 0.83-0.87 (docs/denoising.md). For an image Z
// that is a linear function of the noisy mean X with own weight g (dZ(p)/dX(p)), Stein's unbiased
// risk estimate gives its squared error at each pixel:
//
//   E[(Z - truth)^2] = E[(Z - X)^2] - Var(X) + 2 g Var(X),
//
// and the halves give Var(X) without bias whatever the sampler: (even - odd)^2 weighted by their
// counts (core/film/replicate_variance.h). Each pixel and channel blends the two second-pass
// images and the noisy value with the weights whose estimate, summed over its neighbours (itself
// left out, so its own noise does not choose), is least (core/denoise/candidate_blend.h): the
// noisy value wherever filtering would not help, so the result is never worse than the noisy
// image by its own estimate. The image's error is the mean of the blends' estimates, as rtiow's
// image error (relative RMS, offset 0.01); bias and noise are both in it.

#include <cstdint>
#include <exception>
#include <vector>

#include "core/denoise/denoise_control.h"
#include "core/denoise/denoise_input.h"
#include "core/film/film.h"
#include "core/geometry/vec3.h"

namespace rtiow {

struct DenoisedImage {
  Film image;                     // the denoised image
  Film noisy;                     // the noisy mean it was made from
  std::vector<Vec3d> mse;         // each pixel's estimated squared error per channel (>= 0),
                                  // averaged over 7x7 pixels relative to their levels
  std::vector<float> noisy_kept;  // the noisy value's share in each pixel: 1 where it kept it
  double estimated_error = 0.0;   // the image's relative RMS error (offset 0.01), estimated
  double noisy_error = 0.0;       // the noisy image's, by the same estimate
  double seconds = 0.0;           // the denoiser's own time
};

// The denoiser stopped by its caller (a render's stop or time limit while it judges a round).
class DenoiseCancelled : public std::exception {
 public:
  const char* what() const noexcept override { return "the denoiser was stopped"; }
};

// Deterministic: the same bits for the same input on any number of threads. Throws
// DenoiseCancelled soon after `control` is stopped; its progress, if any, goes from 0 to its
// total as the passes' rows finish.
DenoisedImage denoise(const DenoiseInput& input, const DenoiseControl& control = {});

}  // namespace rtiow
