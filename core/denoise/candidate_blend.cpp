#include "core/denoise/candidate_blend.h"

#include <algorithm>
#include <cstddef>

#include "core/denoise/pixel_loop.h"
#include "core/denoise/window_mean.h"

namespace rtiow {

std::array<double, 2> simplex_minimum(double m11, double m12, double m22, double b1, double b2) {
  const auto objective = [&](double a1, double a2) {
    return a1 * a1 * m11 + 2 * a1 * a2 * m12 + a2 * a2 * m22 - 2 * a1 * b1 - 2 * a2 * b2;
  };
  // The minimum of a convex quadratic over the triangle is its stationary point inside, or the
  // minimum on one of its edges: each tried, the least kept.
  std::array<double, 2> best{0.0, 0.0};
  double least = 0.0;
  const auto consider = [&](double a1, double a2) {
    if (!(a1 >= 0 && a2 >= 0 && a1 + a2 <= 1)) return;  // NaN fails too
    const double value = objective(a1, a2);
    if (value < least) least = value, best = {a1, a2};
  };
  const double det = m11 * m22 - m12 * m12;
  if (det > 0) consider((b1 * m22 - b2 * m12) / det, (b2 * m11 - b1 * m12) / det);
  if (m11 > 0) consider(std::clamp(b1 / m11, 0.0, 1.0), 0.0);  // a2 = 0
  if (m22 > 0) consider(0.0, std::clamp(b2 / m22, 0.0, 1.0));  // a1 = 0
  const double along = m11 - 2 * m12 + m22;                    // a1 + a2 = 1
  if (along > 0) {
    const double t = std::clamp((m22 - m12 + b1 - b2) / along, 0.0, 1.0);
    consider(t, 1.0 - t);
  }
  consider(1.0, 0.0), consider(0.0, 1.0);
  return best;
}

BlendedImage blend_candidates(const DenoiseInput& in,
                              const std::array<FilteredCandidate, 2>& filtered,
                              const std::vector<Vec3d>& variance,
                              const std::vector<Vec3d>& relative_weight, int radius,
                              const DenoiseControl& control) {
  const std::size_t n = in.size();
  BlendedImage out;
  out.color.resize(n), out.error.resize(n);
  std::vector<double> noisy_share(n, 0.0);
  // The neighbourhood sums of M's and b's entries, one channel at a time.
  enum Term { kM11, kM12, kM22, kB1, kB2, kTerms };
  std::array<std::vector<double>, kTerms> terms;
  for (auto& t : terms) t.resize(n);
  const auto difference = [&](int i, std::size_t p, std::size_t c) {
    return double((*filtered[std::size_t(i)].color)[p][c]) - double(in.mean[p][c]);
  };
  for (std::size_t c = 0; c < 3; ++c) {
    for_each_pixel(in.width, in.height, [&](std::size_t p) {
      const double w = relative_weight[p][c], d1 = difference(0, p, c), d2 = difference(1, p, c);
      const double v = w * variance[p][c];
      terms[kM11][p] = w * d1 * d1, terms[kM12][p] = w * d1 * d2, terms[kM22][p] = w * d2 * d2;
      terms[kB1][p] = v * (1.0 - double((*filtered[0].own_weight)[p]));
      terms[kB2][p] = v * (1.0 - double((*filtered[1].own_weight)[p]));
    });
    for (auto& t : terms) t = window_mean(t, in.width, in.height, radius, true);
    for_each_pixel(in.width, in.height, [&](std::size_t p) {
      const auto [a1, a2] = simplex_minimum(terms[kM11][p], terms[kM12][p], terms[kM22][p],
                                            terms[kB1][p], terms[kB2][p]);
      const double dy = a1 * difference(0, p, c) + a2 * difference(1, p, c);
      const double g = 1.0 + a1 * (double((*filtered[0].own_weight)[p]) - 1.0) +
                       a2 * (double((*filtered[1].own_weight)[p]) - 1.0);
      out.color[p][c] = float(std::max(0.0, double(in.mean[p][c]) + dy));
      out.error[p][c] = dy * dy - variance[p][c] * (1.0 - 2.0 * g);
      noisy_share[p] += (1.0 - a1 - a2) / 3.0;
    });
    control.advance(n);
  }
  out.noisy_share.assign(noisy_share.begin(), noisy_share.end());
  return out;
}

}  // namespace rtiow
