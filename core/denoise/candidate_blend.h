#pragma once
// Each pixel's blend of the noisy mean X and two filtered images Z1, Z2 of it, per channel:
//
//   Y = X + a1 (Z1 - X) + a2 (Z2 - X),   a1, a2 >= 0,  a1 + a2 <= 1,
//
// with (a1, a2) the weights whose Stein estimate of the relative squared error, summed over the
// pixel's neighbours (the pixel left out, so its own noise does not choose), is least. Y is a
// linear function of X with own weight g = 1 + a1 (g1 - 1) + a2 (g2 - 1), so its error has
// Stein's estimate like each candidate's:
//
//   E[(Y - truth)^2] = E[(Y - X)^2] - Var(X) + 2 g Var(X),
//
// and over a neighbourhood that estimate is a quadratic in (a1, a2): a^T M a - 2 b^T a + const,
// M the sums of (Z_i - X)(Z_j - X), b those of Var(X) (1 - g_i). Choosing one candidate per
// pixel is the corners of this triangle; the blend reaches the points between them (measured:
// 1-25% less squared error than the choice at 400 pixels wide, docs/denoising.md). a = 0 is the
// noisy value: where neither filter helps its neighbours, a pixel keeps it.

#include <array>
#include <vector>

#include "core/denoise/denoise_control.h"
#include "core/denoise/denoise_input.h"
#include "core/geometry/vec3.h"

namespace rtiow {

// A filtered image of the noisy mean and its own weight in each pixel (d Z(p) / d X(p)).
struct FilteredCandidate {
  const std::vector<Color>* color = nullptr;
  const std::vector<float>* own_weight = nullptr;
};

struct BlendedImage {
  std::vector<Color> color;        // Y, never below 0
  std::vector<Vec3d> error;        // Stein's estimate of Y's squared error, per channel
  std::vector<float> noisy_share;  // 1 - a1 - a2, the mean over the channels
};

// The weights minimising a^T M a - 2 b^T a over the triangle a1, a2 >= 0, a1 + a2 <= 1, for a
// symmetric positive semidefinite M = [m11 m12; m12 m22]; (0, 0) where nothing is lower than 0.
std::array<double, 2> simplex_minimum(double m11, double m12, double m22, double b1, double b2);

// `variance` is Var(X) at each pixel and `relative_weight` each channel's 1 / (level + 0.01)^2,
// so that the neighbourhoods weigh errors as the image's relative error does; the
// neighbourhoods are (2 radius + 1)^2 pixels. Deterministic: the same bits for any thread
// count. Each channel done advances `control` by the image's pixels.
BlendedImage blend_candidates(const DenoiseInput& in,
                              const std::array<FilteredCandidate, 2>& filtered,
                              const std::vector<Vec3d>& variance,
                              const std::vector<Vec3d>& relative_weight, int radius,
                              const DenoiseControl& control = {});

}  // namespace rtiow
