// The denoiser's first pass (core/denoise/equal_weight_regression.h) from window sums, against
// the least squares it stands for, set up and solved directly, neighbour by neighbour.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/denoise/equal_weight_regression.h"

namespace rtiow {
namespace {

// Features with sky (depth 0), silhouettes and albedo edges, and two noisy images.
DenoiseInput random_input(int width, int height, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  DenoiseInput in;
  in.width = width, in.height = height;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const bool sky = (x + 3 * y) % 7 == 0 || y < 2;
      const float depth = sky ? 0.0f : 2.0f + 10.0f * unit(rng);
      in.features.push_back(
          {unit(rng), unit(rng), unit(rng), unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng), depth});
      in.even.push_back({unit(rng), unit(rng), 3.0f * unit(rng)});
      in.odd.push_back({unit(rng), 0.01f * unit(rng), unit(rng)});
      in.mean.push_back((in.even.back() + in.odd.back()) * 0.5f);
      in.even_samples.push_back(4), in.odd_samples.push_back(4);
    }
  }
  return in;
}

// Pixel (px, py)'s fit and own weight, by the regression written out: every neighbour of the
// clipped window a row of the design, the ridge on every column but the intercept.
struct Direct {
  Eigen::Vector3d value[2];
  double own_weight;
};
Direct direct_fit(const DenoiseInput& in, int px, int py) {
  constexpr int kColumns = 10;
  const auto at = [&](int x, int y) {
    return std::size_t(y) * std::size_t(in.width) + std::size_t(x);
  };
  const PixelFeatures& own = in.features[at(px, py)];
  std::vector<Eigen::Matrix<double, kColumns, 1>> rows;
  std::vector<Eigen::Matrix<double, 6, 1>> values;
  for (int y = std::max(0, py - kRegressionRadius);
       y <= std::min(in.height - 1, py + kRegressionRadius); ++y) {
    for (int x = std::max(0, px - kRegressionRadius);
         x <= std::min(in.width - 1, px + kRegressionRadius); ++x) {
      const PixelFeatures& f = in.features[at(x, y)];
      Eigen::Matrix<double, kColumns, 1> row;
      row(0) = 1.0;
      for (int c = 0; c < 6; ++c)
        row(1 + c) = double(f[std::size_t(c)]) - double(own[std::size_t(c)]);
      row(7) = own[6] > 0 ? (double(f[6]) - double(own[6])) / double(own[6]) : f[6] > 0 ? 1.0 : 0.0;
      row(8) = double(x - px) / kRegressionRadius;
      row(9) = double(y - py) / kRegressionRadius;
      rows.push_back(row);
      Eigen::Matrix<double, 6, 1> v;
      for (int c = 0; c < 3; ++c)
        v(c) = in.even[at(x, y)][std::size_t(c)], v(3 + c) = in.odd[at(x, y)][std::size_t(c)];
      values.push_back(v);
    }
  }
  Eigen::Matrix<double, kColumns, kColumns> normal =
      Eigen::Matrix<double, kColumns, kColumns>::Zero();
  Eigen::Matrix<double, kColumns, 6> rhs = Eigen::Matrix<double, kColumns, 6>::Zero();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    normal += rows[i] * rows[i].transpose();
    rhs += rows[i] * values[i].transpose();
  }
  for (int c = 1; c < kColumns; ++c) normal(c, c) += kRegressionRidge * double(rows.size());
  const Eigen::Matrix<double, kColumns, 6> beta = normal.ldlt().solve(rhs);
  const Eigen::Matrix<double, kColumns, kColumns> inverse = normal.inverse();
  Direct out;
  out.value[0] = beta.row(0).head<3>().transpose();
  out.value[1] = beta.row(0).tail<3>().transpose();
  out.own_weight = inverse(0, 0);
  return out;
}

// Images narrower and shorter than the window, and 4100 pixels wide or high, where the place
// columns' window sums (of x / 4 up to 1025, squared) are re-centred on the pixel.
TEST(EqualWeightRegression, IsTheLeastSquaresOverEachWindow) {
  for (const auto& [width, height] : {std::pair{23, 17}, std::pair{5, 3}, std::pair{1, 12},
                                      std::pair{4100, 10}, std::pair{6, 4100}}) {
    const DenoiseInput in = random_input(width, height, std::uint64_t(width * 100 + height));
    const std::vector<FilteredHalf> fitted = regress_equally(in, {&in.even, &in.odd});
    ASSERT_EQ(fitted.size(), 2u);
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const Direct d = direct_fit(in, x, y);
        const std::size_t p = std::size_t(y) * std::size_t(width) + std::size_t(x);
        for (int i = 0; i < 2; ++i)
          for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(fitted[std::size_t(i)].color[p][std::size_t(c)], d.value[i](c),
                        1e-5 * (1.0 + std::abs(d.value[i](c))))
                << width << "x" << height << " pixel " << x << "," << y << " image " << i;
        ASSERT_NEAR(fitted[0].own_weight[p], d.own_weight, 1e-6) << x << "," << y;
        ASSERT_EQ(fitted[1].own_weight[p], fitted[0].own_weight[p]);
      }
    }
    // One image alone: the bits it has beside the other.
    const std::vector<FilteredHalf> alone = regress_equally(in, {&in.odd});
    EXPECT_EQ(alone[0].color, fitted[1].color);
  }
}

}  // namespace
}  // namespace rtiow
