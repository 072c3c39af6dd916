#include "core/denoise/feature_regression.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/parallel/parallel_for_range.h"

namespace rtiow {

namespace {

// The regression's columns: 1 (the estimate at the pixel), the 7 features and the 2 screen
// offsets, each as the neighbour's difference from the pixel, so the intercept is the value at
// the pixel and its hat entry is the (0, 0) entry of the inverse normal matrix.
constexpr int kColumns = 1 + int(FirstHitSum::kChannels) + 2;
constexpr int kWindow = (2 * kRegressionRadius + 1) * (2 * kRegressionRadius + 1);
// A small ridge on every column but the intercept, relative to the weights' sum: windows where a
// feature is constant (one material, the sky) leave its column zero.
constexpr double kRidge = 1e-3;

using Design = Eigen::Matrix<double, Eigen::Dynamic, kColumns, Eigen::RowMajor, kWindow, kColumns>;
using Values = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor, kWindow, 3>;
using Weights = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kWindow, 1>;
using Normal = Eigen::Matrix<double, kColumns, kColumns>;
using Solution = Eigen::Matrix<double, kColumns, 4>;

// A feature's difference from the pixel's, on a scale of about one: albedo and normal as they
// are; depth relative to the larger of the two (0 where both are the sky).
double feature_difference(const PixelFeatures& q, const PixelFeatures& p, std::size_t c) {
  if (c + 1 < FirstHitSum::kChannels) return double(q[c]) - double(p[c]);
  const double larger = std::max(double(q[c]), double(p[c]));
  return larger > 0 ? (double(q[c]) - double(p[c])) / larger : 0.0;
}

// Rousselle et al.'s patch distance between pixels p and q of `guide` (variance `variance`),
// for a bandwidth of 1: over the patch and the channels, the squared difference less what the
// noise explains, over the noise's level. Divide by k^2 for bandwidth k.
double patch_distance(const std::vector<Color>& guide, const std::vector<Vec3d>& variance,
                      const DenoiseInput& in, int px, int py, int qx, int qy) {
  double total = 0.0;
  int terms = 0;
  for (int dy = -kPatchRadius; dy <= kPatchRadius; ++dy) {
    for (int dx = -kPatchRadius; dx <= kPatchRadius; ++dx) {
      const int ax = px + dx, ay = py + dy, bx = qx + dx, by = qy + dy;
      if (ax < 0 || ay < 0 || bx < 0 || by < 0 || ax >= in.width || bx >= in.width ||
          ay >= in.height || by >= in.height)
        continue;
      // The guide's value at p itself is never read: its noise would choose p's weights,
      // and its half's mean at p is part of the noisy value the error is measured against.
      if ((ax == px && ay == py) || (bx == px && by == py)) continue;
      const std::size_t a = std::size_t(ay) * std::size_t(in.width) + std::size_t(ax);
      const std::size_t b = std::size_t(by) * std::size_t(in.width) + std::size_t(bx);
      for (std::size_t c = 0; c < 3; ++c) {
        const double diff = double(guide[a][c]) - double(guide[b][c]);
        const double va = variance[a][c], vb = variance[b][c];
        total += (diff * diff - (va + std::min(va, vb))) / (1e-12 + va + vb);
        ++terms;
      }
    }
  }
  return terms ? std::max(0.0, total / terms) : 0.0;
}

struct Regressed {
  Eigen::Vector3d value;
  double own_weight;
};

// The weighted least squares fit at the window's pixel (row `self`): the normal equations
// gathered row by row as rank-one updates of their lower half (a general matrix product spent
// more time packing the 10 x 121 operands than multiplying them), rows of weight 0 skipped.
Regressed fit(const Design& x, const Weights& w, const Values& y, int self) {
  Normal normal = Normal::Zero();
  Solution rhs = Solution::Zero();
  double total = 0.0;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    if (w(i) == 0.0) continue;
    const Eigen::Matrix<double, kColumns, 1> row = x.row(i).transpose();
    normal.selfadjointView<Eigen::Lower>().rankUpdate(row, w(i));
    rhs.leftCols<3>().noalias() += (w(i) * row) * y.row(i);
    total += w(i);
  }
  for (int c = 1; c < kColumns; ++c) normal(c, c) += kRidge * total;
  rhs(0, 3) = 1.0;
  const Solution beta = normal.ldlt().solve(rhs);  // LDLT reads the lower half
  return {beta.block<1, 3>(0, 0).transpose(), w(self) * beta(0, 3)};
}

}  // namespace

std::vector<FilteredHalf> filter_half(const DenoiseInput& in, const std::vector<Color>& half,
                                      const Guide& guide, const std::vector<float>& bandwidths) {
  const std::size_t n = in.size();
  const std::size_t results = guide.image ? bandwidths.size() : 1;
  std::vector<FilteredHalf> out(results);
  for (FilteredHalf& f : out) f.color.resize(n), f.own_weight.resize(n);

  parallel_for_range(std::size_t(in.height), 1, [&](std::size_t y0, std::size_t y1) {
    Design x;
    Values values;
    Weights distance, w;
    for (int py = int(y0); py < int(y1); ++py) {
      for (int px = 0; px < in.width; ++px) {
        const std::size_t p = std::size_t(py) * std::size_t(in.width) + std::size_t(px);
        const int qx0 = std::max(0, px - kRegressionRadius);
        const int qx1 = std::min(in.width - 1, px + kRegressionRadius);
        const int qy0 = std::max(0, py - kRegressionRadius);
        const int qy1 = std::min(in.height - 1, py + kRegressionRadius);
        const int rows = (qx1 - qx0 + 1) * (qy1 - qy0 + 1);
        x.resize(rows, kColumns), values.resize(rows, 3), distance.resize(rows), w.resize(rows);
        int row = 0, self = 0;
        for (int qy = qy0; qy <= qy1; ++qy) {
          for (int qx = qx0; qx <= qx1; ++qx, ++row) {
            const std::size_t q = std::size_t(qy) * std::size_t(in.width) + std::size_t(qx);
            if (q == p) self = row;
            x(row, 0) = 1.0;
            for (std::size_t c = 0; c < FirstHitSum::kChannels; ++c)
              x(row, 1 + int(c)) = feature_difference(in.features[q], in.features[p], c);
            x(row, kColumns - 2) = double(qx - px) / kRegressionRadius;
            x(row, kColumns - 1) = double(qy - py) / kRegressionRadius;
            for (int c = 0; c < 3; ++c) values(row, c) = half[q][std::size_t(c)];
            distance(row) = guide.image
                                ? patch_distance(*guide.image, *guide.variance, in, px, py, qx, qy)
                                : 0.0;
          }
        }
        for (std::size_t k = 0; k < results; ++k) {
          const double scale =
              guide.image ? 1.0 / (double(bandwidths[k]) * double(bandwidths[k])) : 0.0;
          // Weights below e^-30 are 0: they change nothing, and as subnormal numbers they made
          // the products several times slower.
          w = (distance.array() * scale)
                  .unaryExpr([](double d) { return d < 30.0 ? std::exp(-d) : 0.0; })
                  .matrix();
          const Regressed fitted = fit(x, w, values, self);
          out[k].color[p] = {float(fitted.value[0]), float(fitted.value[1]),
                             float(fitted.value[2])};
          out[k].own_weight[p] = float(fitted.own_weight);
        }
      }
    }
  });
  return out;
}

}  // namespace rtiow
