#include "core/denoise/feature_regression.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>

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
constexpr std::size_t kRowsPerChunk = 8;
static_assert(kPatchRadius == 1, "PatchDistances keeps the terms of three rows");

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

// Rousselle et al.'s patch distance between pixels p and q = p + d of a guide (each pixel with
// its variance), for a bandwidth of 1: over the patch and the channels, the squared difference
// less what the noise explains, over the noise's level; divide by k^2 for bandwidth k. The
// guide's value at p itself is never read: its noise would choose p's weights, and its half's
// mean at p is part of the noisy value the error is measured against.
//
// Each term belongs to one pixel a of p's patch and the offset d (a against a + d), and the same
// term falls in the patches of nine pixels: the terms of every offset are computed once for
// each row and kept for three rows, and a distance sums its patch's nine.
class PatchDistances {
 public:
  PatchDistances(const DenoiseInput& in, const Guide& guide)
      : in_(in), guide_(guide), width_(std::size_t(in.width)) {
    terms_.resize(kOffsets * 3 * width_);
    valid_.resize(kOffsets * 3 * width_);
  }

  // Makes the terms of rows py - 1 to py + 1 ready (rows asked in increasing order).
  void at_row(int py) {
    const int last = std::min(py + 1, in_.height - 1);
    for (int row = std::max(py - 1, next_row_); row <= last; ++row) compute_row(row);
    next_row_ = std::max(next_row_, last + 1);
  }

  double distance(int px, int py, int dx, int dy) const {
    const int offset = offset_index(dx, dy);
    double total = 0.0;
    int terms = 0;
    for (int ay = std::max(0, py - kPatchRadius); ay <= std::min(in_.height - 1, py + kPatchRadius);
         ++ay) {
      for (int ax = std::max(0, px - kPatchRadius);
           ax <= std::min(in_.width - 1, px + kPatchRadius); ++ax) {
        const std::size_t at = slot(offset, ay) + std::size_t(ax);
        total += terms_[at], terms += valid_[at];
      }
    }
    // p itself, and the pixel whose partner is p: their terms read the guide at p.
    const auto leave_out = [&](int ax, int ay) {
      const std::size_t at = slot(offset, ay) + std::size_t(ax);
      total -= terms_[at], terms -= valid_[at];
    };
    leave_out(px, py);
    const int ax = px - dx, ay = py - dy;
    if ((dx != 0 || dy != 0) && std::abs(dx) <= kPatchRadius && std::abs(dy) <= kPatchRadius &&
        ax >= 0 && ay >= 0 && ax < in_.width && ay < in_.height)
      leave_out(ax, ay);
    return terms > 0 ? std::max(0.0, total / (3.0 * terms)) : 0.0;
  }

 private:
  static constexpr int kSide = 2 * kRegressionRadius + 1;
  static constexpr std::size_t kOffsets = std::size_t(kSide) * std::size_t(kSide);

  static int offset_index(int dx, int dy) {
    return (dy + kRegressionRadius) * kSide + (dx + kRegressionRadius);
  }
  std::size_t slot(int offset, int row) const {
    return (std::size_t(offset) * 3 + std::size_t(row % 3)) * width_;
  }

  void compute_row(int ay) {
    const std::vector<Color>& g = *guide_.image;
    const std::vector<Vec3d>& v = *guide_.variance;
    for (int dy = -kRegressionRadius; dy <= kRegressionRadius; ++dy) {
      for (int dx = -kRegressionRadius; dx <= kRegressionRadius; ++dx) {
        const std::size_t base = slot(offset_index(dx, dy), ay);
        const int by = ay + dy;
        for (int ax = 0; ax < in_.width; ++ax) {
          const int bx = ax + dx;
          double term = 0.0;
          const bool inside = bx >= 0 && by >= 0 && bx < in_.width && by < in_.height;
          if (inside) {
            const std::size_t a = std::size_t(ay) * width_ + std::size_t(ax);
            const std::size_t b = std::size_t(by) * width_ + std::size_t(bx);
            for (std::size_t c = 0; c < 3; ++c) {
              const double diff = double(g[a][c]) - double(g[b][c]);
              const double va = v[a][c], vb = v[b][c];
              term += (diff * diff - (va + std::min(va, vb))) / (1e-12 + va + vb);
            }
          }
          terms_[base + std::size_t(ax)] = term;
          valid_[base + std::size_t(ax)] = inside ? 1 : 0;
        }
      }
    }
  }

  const DenoiseInput& in_;
  const Guide& guide_;
  std::size_t width_;
  int next_row_ = 0;
  std::vector<double> terms_;  // [offset][row mod 3][x]
  std::vector<int> valid_;     // 1 where the term's two pixels are in the image
};

struct Regressed {
  Eigen::Vector3d value;
  double own_weight;
};

// The weighted least squares fit at the window's pixel (row `self`): the normal equations
// gathered row by row as fixed-size outer products, which Eigen unrolls (a general matrix
// product spent more time packing the 10 x 121 operands than multiplying them, and a rank update
// of the lower half alone ran as a call per row), rows of weight 0 skipped.
Regressed fit(const Design& x, const Weights& w, const Values& y, int self) {
  Normal normal = Normal::Zero();
  Solution rhs = Solution::Zero();
  double total = 0.0;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    if (w(i) == 0.0) continue;
    const Eigen::Matrix<double, kColumns, 1> row = x.row(i).transpose();
    normal.noalias() += (w(i) * row) * row.transpose();
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
                                      const Guide& guide, const std::vector<float>& bandwidths,
                                      const std::function<bool()>& cancelled) {
  const std::size_t n = in.size();
  const std::size_t results = guide.image ? bandwidths.size() : 1;
  std::vector<FilteredHalf> out(results);
  for (FilteredHalf& f : out) f.color.resize(n), f.own_weight.resize(n);

  // Chunks of rows, so that each row's patch terms serve the rows around it.
  parallel_for_range(std::size_t(in.height), kRowsPerChunk, [&](std::size_t y0, std::size_t y1) {
    Design x;
    Values values;
    Weights distance, w;
    std::optional<PatchDistances> patches;
    if (guide.image) patches.emplace(in, guide);
    for (int py = int(y0); py < int(y1); ++py) {
      if (cancelled && cancelled()) return;
      if (patches) patches->at_row(py);
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
            distance(row) = patches ? patches->distance(px, py, qx - px, qy - py) : 0.0;
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
