#pragma once
// The denoiser's second pass: for each pixel, a first-order regression of one half's colour on
// the first hit's features (albedo, normal, depth) and the pixel's place, over a window around it
// (Bitterli et al. 2016, "Nonlinearly Weighted First-order Regression for Denoising Monte Carlo
// Renderings", section 4), its neighbours weighted by non-local means on a guide (the patch
// distance of Rousselle et al. 2012, "Adaptive Rendering with Non-Local Means Filtering", eq. 6);
// or, with the guide's weights, their weighted mean. (The first pass, the same regression with
// equal weights: core/denoise/equal_weight_regression.h.) The guide is made from the other
// half alone, so the filtered half stays a linear function of its own samples, whose share in its
// own pixel (the hat matrix's diagonal) the error estimate needs (core/denoise/denoiser.h).

#include <array>
#include <vector>

#include "core/denoise/denoise_control.h"
#include "core/denoise/denoise_input.h"
#include "core/geometry/vec3.h"

namespace rtiow {

// The window is (2 kRegressionRadius + 1)^2 pixels; the patches (2 kPatchRadius + 1)^2. 9x9
// gave 1-37% more squared error gain than 11x11 in 22 of 24 cases (the 400-pixel `materials` at
// 8 and 32 spp 1-3% less) in 0.74x the time; 7x7 more still, but its estimate read 0.78 of the
// truth on `defocus` at 8 spp (docs/denoising.md).
inline constexpr int kRegressionRadius = 4;
inline constexpr int kPatchRadius = 1;
// The columns one task filters at a time: the patch terms it keeps (81 offsets, three rows, 16
// bytes a column each) then stay within a core's cache whatever the image's width (the whole
// rows' took 6 MB at 1600 pixels wide; 12% of the denoiser's time there). A multiple of the four
// pixels fitted at once.
inline constexpr int kColumnsPerTile = 256;
// A small ridge on every column but the intercept, relative to the weights' sum: windows where a
// feature is constant (one material, the sky) leave its column zero.
inline constexpr double kRegressionRidge = 1e-3;

// What weighs a pixel's neighbours: the patches of `image`, whose pixels have `variance`.
struct Guide {
  const std::vector<Color>* image = nullptr;
  const std::vector<Vec3d>* variance = nullptr;
};

// How a pixel's neighbours, weighted by the guide, make its value: a first-order regression on
// the features (follows shading that they explain, at the variance of fitting ten columns), or
// their weighted mean (far less variance where the guide finds similar neighbours, biased where
// the features vary across them).
enum class Fit { kRegression, kMean };

// One of the second pass's filters: its bandwidth (how far, in standard deviations of the
// guide's noise, a neighbour's patch may differ and still count) and its fit.
struct Weighting {
  float bandwidth = 1.0f;
  Fit fit = Fit::kRegression;
};

// One half filtered: each pixel's value, and its own weight in it (d filtered(p) / d half(p),
// the hat matrix's diagonal).
struct FilteredHalf {
  std::vector<Color> color;
  std::vector<float> own_weight;
};

// `half` (one of `in`'s halves) filtered with each weighting of `weightings`, its neighbours
// weighted by `guide` (which must hold an image and its variance). Deterministic: the same bits
// for any thread count and any `columns_per_tile` (a positive multiple of 4; the tests vary it).
// Rows are left unfiltered once `control` is stopped (the caller asks it again and throws the
// work away); each row of a tile done advances it by the tile's width.
std::vector<FilteredHalf> filter_half(const DenoiseInput& in, const std::vector<Color>& half,
                                      const Guide& guide, const std::vector<Weighting>& weightings,
                                      const DenoiseControl& control = {},
                                      int columns_per_tile = kColumnsPerTile);

}  // namespace rtiow
