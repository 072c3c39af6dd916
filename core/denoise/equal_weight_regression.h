#pragma once
// The denoiser's first pass: each image regressed, pixel by pixel, on the first hit's albedo and
// normal and the pixel's place over the window around it, every neighbour weighted the same
// (Bitterli et al. 2016, section 4, with equal weights). With equal weights and columns that are
// each a neighbour's value less the pixel's, the normal equations are window sums of products of
// the neighbours' own values, re-centred on the pixel: a sum over the window's columns of sums
// over its rows, the same for every pixel of a column, instead of a pass over every neighbour of
// every pixel.

#include <vector>

#include "core/denoise/denoise_control.h"
#include "core/denoise/denoise_input.h"
#include "core/denoise/feature_regression.h"

namespace rtiow {

// Each of `images` (one or two of `in`'s halves) filtered: [image]. Deterministic: the same bits
// for any thread count and in every instruction set's build. Rows are left unfiltered once
// `control` is stopped (the caller asks it again and throws the work away); each row done
// advances it by the image's width.
std::vector<FilteredHalf> regress_equally(const DenoiseInput& in,
                                          const std::vector<const std::vector<Color>*>& images,
                                          const DenoiseControl& control = {});

}  // namespace rtiow
