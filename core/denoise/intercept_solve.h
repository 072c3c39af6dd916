#pragma once
// The one solve both of the denoiser's regressions make a pixel. Of the normal equations
// N b = X'W y only the fit at the pixel is wanted, the intercept e0' N^-1 X'W y (every column is a
// neighbour's value less the pixel's), so one solve of N z = e0 gives it for every image fitted on
// the same design and weights, and z(0) is the hat matrix's diagonal over the pixel's own weight.

#include <Eigen/Dense>

namespace rtiow {

// The first row of N^-1, N symmetric with its lower half given: positive definite with the ridge,
// so Eigen's Cholesky factorisation solves it; where rounding says otherwise (features of wildly
// different scales), the pivoting LDLT.
template <int Columns>
Eigen::Matrix<double, Columns, 1> inverse_first_row(
    const Eigen::Matrix<double, Columns, Columns>& normal) {
  const auto unit = Eigen::Matrix<double, Columns, 1>::Unit(0);
  const Eigen::LLT<Eigen::Matrix<double, Columns, Columns>, Eigen::Lower> cholesky(normal);
  if (cholesky.info() == Eigen::Success) return cholesky.solve(unit);
  return normal.template selfadjointView<Eigen::Lower>().ldlt().solve(unit);
}

}  // namespace rtiow
