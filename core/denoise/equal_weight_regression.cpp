#include "core/denoise/equal_weight_regression.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cstddef>
#include <stdexcept>
#include <utility>

#include <oneapi/tbb/enumerable_thread_specific.h>

#include "core/denoise/intercept_solve.h"
#include "core/parallel/instruction_sets.h"
#include "core/parallel/parallel_for_range.h"

namespace rtiow {

// Named inside the anonymous namespace: the core is built as unity sources, where two files'
// anonymous namespaces are one.
namespace {
namespace equal_weights {

// The design's columns, each a neighbour's value less the pixel's: 1 (the intercept: the fit at
// the pixel), albedo (3), normal (3), depth and place (2, in window radii). Depth as the second
// pass's column is about one across a silhouette (core/denoise/feature_regression.cpp), but
// relative to the farther of the two pixels it is no difference of their values: here it is
// relative to the pixel's own depth, and where the pixel is the sky (depth 0), whether the
// neighbour is not (1 or 0, as there). A scaled column changes only how much the ridge holds it.
// Without depth this pass's image guided as well on three scenes and lost 9% of the squared
// error gain on `viewpoint` at 8 spp (2026-11-30, docs/denoising.md).
constexpr int kColumns = 10;
constexpr int kDepthColumn = 7;
// The values a pixel's window sums are taken of: the columns' before centring, with two for
// depth (the depth itself, and whether the first hit is not the sky), then each image's three
// channels.
enum Plane { kOne, kFeature0, kDepth = 7, kHit, kPlaceX, kPlaceY, kImage0 };
constexpr int kMostImages = 2;
constexpr int kPlanes = kImage0 + 3 * kMostImages;
constexpr std::size_t kRowsPerChunk = 8;
constexpr int kSide = 2 * kRegressionRadius + 1;

using Normal = Eigen::Matrix<double, kColumns, kColumns>;
using Column = Eigen::Matrix<double, kColumns, 1>;

// The products whose window sums the normal equations need: each plane of the design with each
// at or after it, and with each image's channels.
struct Products {
  std::array<std::array<int, 2>, kImage0*(kImage0 + 1) / 2 + kImage0 * 3 * kMostImages> pair{};
  std::array<std::array<int, kPlanes>, kImage0> index{};  // [plane][plane] -> pair, a <= b
  int count = 0;

  explicit Products(int images) {
    for (int a = 0; a < kImage0; ++a) {
      for (int b = a; b < kImage0 + 3 * images; ++b) {
        index[std::size_t(a)][std::size_t(b)] = count;
        pair[std::size_t(count++)] = {a, b};
      }
    }
  }
  std::size_t of(int a, int b) const {
    const auto low = std::size_t(std::min(a, b)), high = std::size_t(std::max(a, b));
    return std::size_t(index[low % kImage0][high % kPlanes]);  // a, b < kPlanes
  }
};

// A chunk's rows and the window's rows around them, a value at a time: [value][row][x].
struct RowPlanes {
  std::vector<double> data;
  int first_row = 0, rows = 0, width = 0;

  const double* at(int value, int y) const {
    return &data[(std::size_t(value) * std::size_t(rows) + std::size_t(y - first_row)) *
                 std::size_t(width)];
  }
  double* at(int value, int y) { return const_cast<double*>(std::as_const(*this).at(value, y)); }
};

void fill_planes(const DenoiseInput& in, const std::vector<const std::vector<Color>*>& images,
                 int first_row, int last_row, RowPlanes& out) {
  out.first_row = first_row, out.rows = last_row - first_row + 1, out.width = in.width;
  out.data.resize(std::size_t(kPlanes) * std::size_t(out.rows) * std::size_t(in.width));
  for (int y = first_row; y <= last_row; ++y) {
    for (int x = 0; x < in.width; ++x) {
      const std::size_t q = std::size_t(y) * std::size_t(in.width) + std::size_t(x);
      const PixelFeatures& f = in.features[q];
      out.at(0, y)[x] = 1.0;
      for (int c = 0; c < 6; ++c) out.at(kFeature0 + c, y)[x] = double(f[std::size_t(c)]);
      const double depth = double(f[6]);
      out.at(kDepth, y)[x] = depth;
      out.at(kHit, y)[x] = depth > 0 ? 1.0 : 0.0;
      out.at(kPlaceX, y)[x] = double(x) / kRegressionRadius;
      out.at(kPlaceY, y)[x] = double(y) / kRegressionRadius;
      for (std::size_t i = 0; i < images.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c)
          out.at(kImage0 + int(3 * i + c), y)[x] = double((*images[i])[q][c]);
    }
  }
}

// Row py's window sums of every product: sums[k][x] is the sum over the window around (x, py),
// clipped to the image, of product k. Each is summed over the window's rows (in their order) for
// every column, then over the window's columns (in theirs, a column outside the image adding
// +0.0): the same operations, in the same order, in every build.
RTIOW_DISPATCHED void window_sums(const RowPlanes& planes, const Products& products, int py,
                                  int height, double* __restrict padded, double* __restrict sums) {
  const int width = planes.width;
  const int y0 = std::max(0, py - kRegressionRadius);
  const int y1 = std::min(height - 1, py + kRegressionRadius);
  double* __restrict column = padded + kRegressionRadius;
  for (int k = 0; k < products.count; ++k) {
    const auto [a, b] = products.pair[std::size_t(k)];
    {
      const double* __restrict pa = planes.at(a, y0);
      const double* __restrict pb = planes.at(b, y0);
      for (int x = 0; x < width; ++x) column[x] = pa[x] * pb[x];
    }
    for (int y = y0 + 1; y <= y1; ++y) {
      const double* __restrict pa = planes.at(a, y);
      const double* __restrict pb = planes.at(b, y);
      for (int x = 0; x < width; ++x) column[x] += pa[x] * pb[x];
    }
    double* __restrict out = sums + std::size_t(k) * std::size_t(width);
    for (int x = 0; x < width; ++x) out[x] = padded[x];
    for (int o = 1; o < kSide; ++o)
      for (int x = 0; x < width; ++x) out[x] += padded[x + o];
  }
}

// Pixel (x, py)'s fits from its window sums. With c the pixel's own values (0 for the
// intercept), s the sums of the columns and m their count, the centred normal matrix is
// S - c s' - s c' + m c c' and the centred right-hand side T - c t', t the images' sums: the
// regression's normal equations with every column a neighbour's value less the pixel's, whose
// first inverse row z gives the fit at the pixel (z' X'y) and its own weight z(0).
void fit_pixel(const RowPlanes& planes, const Products& products, const double* sums,
               std::size_t width, int x, int py, int images, std::vector<FilteredHalf>& out) {
  const auto sum = [&](int a, int b) { return sums[products.of(a, b) * width + std::size_t(x)]; };
  // Each column's plane and scale. Depth: relative to the pixel's own where the pixel is not the
  // sky; where it is, whether the neighbour is not (as the second pass's column: 1 or 0).
  const double own_depth = planes.at(kDepth, py)[x];
  const bool sky = planes.at(kHit, py)[x] == 0.0;
  std::array<int, kColumns> plane{kOne,          kFeature0,     kFeature0 + 1, kFeature0 + 2,
                                  kFeature0 + 3, kFeature0 + 4, kFeature0 + 5, sky ? kHit : kDepth,
                                  kPlaceX,       kPlaceY};
  Column scale = Column::Ones();
  if (!sky) scale(kDepthColumn) = 1.0 / own_depth;
  Column own;
  for (int a = 0; a < kColumns; ++a)
    own(a) = a == 0 ? 0.0 : planes.at(plane[std::size_t(a)], py)[x];
  const double count = sum(kOne, kOne);
  Normal normal = Normal::Zero();
  for (int a = 0; a < kColumns; ++a) {
    const int pa = plane[std::size_t(a)];
    for (int b = 0; b <= a; ++b) {
      const int pb = plane[std::size_t(b)];
      normal(a, b) = (sum(pa, pb) - own(a) * sum(kOne, pb) - sum(kOne, pa) * own(b) +
                      count * own(a) * own(b)) *
                     (scale(a) * scale(b));
    }
  }
  for (int a = 1; a < kColumns; ++a) normal(a, a) += kRegressionRidge * count;
  const Column z = inverse_first_row(normal);
  const std::size_t p = std::size_t(py) * width + std::size_t(x);
  for (int i = 0; i < images; ++i) {
    Vec3d value;
    for (int c = 0; c < 3; ++c) {
      const int channel = kImage0 + 3 * i + c;
      const double image_sum = sum(kOne, channel);
      double v = 0.0;
      for (int a = 0; a < kColumns; ++a)
        v += z(a) * ((sum(plane[std::size_t(a)], channel) - own(a) * image_sum) * scale(a));
      value[std::size_t(c)] = v;
    }
    out[std::size_t(i)].color[p] = Color(value);  // rounded once, as the other fits
    out[std::size_t(i)].own_weight[p] = float(z(0));
  }
}

}  // namespace equal_weights
}  // namespace

std::vector<FilteredHalf> regress_equally(const DenoiseInput& in,
                                          const std::vector<const std::vector<Color>*>& images,
                                          const DenoiseControl& control) {
  using namespace equal_weights;
  if (images.empty() || images.size() > std::size_t(kMostImages))
    throw std::invalid_argument("regress_equally: 1 to 2 images");
  const std::size_t n = in.size(), width = std::size_t(in.width);
  std::vector<FilteredHalf> out(images.size());
  for (FilteredHalf& f : out) f.color.resize(n), f.own_weight.resize(n);
  const Products products(int(images.size()));
  // Each thread's working memory, kept from chunk to chunk.
  struct Scratch {
    RowPlanes planes;
    std::vector<double> padded, sums;
  };
  tbb::enumerable_thread_specific<Scratch> scratch;
  parallel_for_range(std::size_t(in.height), kRowsPerChunk, [&](std::size_t y0, std::size_t y1) {
    Scratch& local = scratch.local();
    local.padded.assign(width + 2 * std::size_t(kRegressionRadius), 0.0);
    local.sums.resize(std::size_t(products.count) * width);
    fill_planes(in, images, std::max(0, int(y0) - kRegressionRadius),
                std::min(in.height - 1, int(y1) - 1 + kRegressionRadius), local.planes);
    for (int py = int(y0); py < int(y1); ++py) {
      if (control.stop()) return;
      window_sums(local.planes, products, py, in.height, local.padded.data(), local.sums.data());
      for (int x = 0; x < in.width; ++x)
        fit_pixel(local.planes, products, local.sums.data(), width, x, py, int(images.size()), out);
      control.advance(width);
    }
  });
  return out;
}

}  // namespace rtiow
