#include "core/denoise/feature_regression.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>

#include <oneapi/tbb/enumerable_thread_specific.h>

#include "core/denoise/intercept_solve.h"
#include "core/denoise/pixel_loop.h"
#include "core/film/pixel_variance.h"
#include "core/parallel/instruction_sets.h"
#include "core/parallel/lanes.h"
#include "core/parallel/parallel_for_range.h"

namespace rtiow {

namespace {

// The regression's columns: 1 (the estimate at the pixel), the 7 features and the 2 screen
// offsets, each as the neighbour's difference from the pixel, so the intercept is the value at
// the pixel and its hat entry is the (0, 0) entry of the inverse normal matrix.
constexpr int kColumns = 1 + int(FirstHitSum::kChannels) + 2;
constexpr std::size_t kRowsPerChunk = 8;

static_assert(kPatchRadius == 1, "PatchDistances keeps the terms of three rows");

using Normal = Eigen::Matrix<double, kColumns, kColumns>;

// The guide and its variance a channel at a time, in doubles: the patch terms' loop reads
// them a vector of pixels at a time. Patches are compared on a square-root scale, sqrt(y +
// 0.01) (rtiow's relative error offset), its variance carried over to first order: a
// difference between dark values then counts for more against one between bright values, as
// in the relative error the denoiser is judged by. Measured 2026-11-30 against the values as
// they are (32 renders, docs/denoising.md): 2% more squared error gain in the geometric mean,
// 3-12% at 8 spp on `materials` and `defocus`; a logarithm gave the same.
struct GuidePlanes {
  std::array<std::vector<double>, 3> value, variance;

  GuidePlanes(const Guide& guide, int width, int height) {
    const std::size_t n = guide.image->size();
    for (std::size_t c = 0; c < 3; ++c) value[c].resize(n), variance[c].resize(n);
    for_each_pixel(width, height, [&](std::size_t p) {
      for (std::size_t c = 0; c < 3; ++c) {
        const double level = std::max(0.0, double((*guide.image)[p][c])) + kRelativeErrorOffset;
        value[c][p] = std::sqrt(level);
        variance[c][p] = (*guide.variance)[p][c] / (4.0 * level);
      }
    });
  }
};

// The patch terms of `count` pixels a = a0.. against b = b0.. (both in the image): over the
// channels, the squared difference less what the noise explains, over the noise's level.
RTIOW_DISPATCHED void patch_terms(const GuidePlanes& g, std::size_t a0, std::size_t b0,
                                  std::size_t count, double* __restrict terms,
                                  double* __restrict valid) {
  const double* __restrict ga[3] = {&g.value[0][a0], &g.value[1][a0], &g.value[2][a0]};
  const double* __restrict gb[3] = {&g.value[0][b0], &g.value[1][b0], &g.value[2][b0]};
  const double* __restrict va[3] = {&g.variance[0][a0], &g.variance[1][a0], &g.variance[2][a0]};
  const double* __restrict vb[3] = {&g.variance[0][b0], &g.variance[1][b0], &g.variance[2][b0]};
  for (std::size_t i = 0; i < count; ++i) {
    double term = 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
      const double diff = ga[c][i] - gb[c][i];
      term +=
          (diff * diff - (va[c][i] + std::min(va[c][i], vb[c][i]))) / (1e-12 + va[c][i] + vb[c][i]);
    }
    terms[i] = term;
    valid[i] = 1.0;
  }
}

// Rousselle et al.'s patch distance between pixels p and q = p + d of a guide (each pixel with
// its variance), for a bandwidth of 1: over the patch and the channels, the squared difference
// less what the noise explains, over the noise's level; divide by k^2 for bandwidth k. The
// guide's value at p itself is never read: its noise would choose p's weights, and its half's
// mean at p is part of the noisy value the error is measured against.
//
// Each term belongs to one pixel a of p's patch and the offset d (a against a + d), and the same
// term falls in the patches of nine pixels: the terms of every offset are computed once for
// each row and kept for three rows, and a distance sums its patch's nine. Only the columns of a
// tile of pixels and their patches' are kept (each term is the same whatever the tile).
class PatchDistances {
 public:
  PatchDistances(const DenoiseInput& in, const GuidePlanes& planes, int columns_per_tile)
      : in_(in), planes_(planes), width_(std::size_t(columns_per_tile + 2 * kPatchRadius)) {
    terms_.resize(kOffsets * 3 * width_);
    valid_.resize(kOffsets * 3 * width_);
  }

  // Forgets the rows computed: a new chunk of rows starts, for the pixels of columns [x0, x1)
  // (at most the tile's columns).
  void restart(int x0, int x1) {
    next_row_ = 0;
    x0_ = std::max(0, x0 - kPatchRadius);
    x1_ = std::min(in_.width, x1 + kPatchRadius);
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
    double terms = 0;
    for (int ay = std::max(0, py - kPatchRadius); ay <= std::min(in_.height - 1, py + kPatchRadius);
         ++ay) {
      for (int ax = std::max(0, px - kPatchRadius);
           ax <= std::min(in_.width - 1, px + kPatchRadius); ++ax) {
        const std::size_t at = slot(offset, ay) + std::size_t(ax - x0_);
        total += terms_[at], terms += valid_[at];
      }
    }
    // p itself, and the pixel whose partner is p: their terms read the guide at p.
    const auto leave_out = [&](int ax, int ay) {
      const std::size_t at = slot(offset, ay) + std::size_t(ax - x0_);
      total -= terms_[at], terms -= valid_[at];
    };
    leave_out(px, py);
    const int ax = px - dx, ay = py - dy;
    if ((dx != 0 || dy != 0) && std::abs(dx) <= kPatchRadius && std::abs(dy) <= kPatchRadius &&
        ax >= 0 && ay >= 0 && ax < in_.width && ay < in_.height)
      leave_out(ax, ay);
    return terms > 0 ? std::max(0.0, total / (3.0 * terms)) : 0.0;
  }

  // Whether the patches of the pixels (px0 .. px0 + kLanes - 1, py) are whole inside the image,
  // as distances() needs.
  bool lanes_inside(int px0, int py) const {
    return px0 >= kPatchRadius && px0 + kLanes - 1 + kPatchRadius < in_.width &&
           py >= kPatchRadius && py + kPatchRadius < in_.height;
  }

  // distance() of the pixels (px0 + l, py), l < kLanes, at the same offset, one per lane, each
  // lane summing its patch in distance()'s order (the same bits); where lanes_inside().
  [[gnu::always_inline]] void distances(int px0, int py, int dx, int dy, Lanes& out) const {
    const int offset = offset_index(dx, dy);
    Lanes total{}, terms{};
    const auto add = [&](int ax, int ay, double sign) {
      const std::size_t at = slot(offset, ay) + std::size_t(ax - x0_);
      Lanes term, valid;
      std::memcpy(&term, &terms_[at], sizeof term);
      std::memcpy(&valid, &valid_[at], sizeof valid);
      if (sign > 0)
        total += term, terms += valid;
      else
        total -= term, terms -= valid;
    };
    for (int ay = py - kPatchRadius; ay <= py + kPatchRadius; ++ay)
      for (int ax = px0 - kPatchRadius; ax <= px0 + kPatchRadius; ++ax) add(ax, ay, 1);
    add(px0, py, -1);
    if ((dx != 0 || dy != 0) && std::abs(dx) <= kPatchRadius && std::abs(dy) <= kPatchRadius)
      add(px0 - dx, py - dy, -1);
    const Lanes d = total / (3.0 * terms);
    out = terms > 0 ? (Lanes{} < d ? d : Lanes{}) : Lanes{};
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

  // The terms of row ay for the columns [x0_, x1_), kept from x0_ on.
  void compute_row(int ay) {
    const std::size_t image_width = std::size_t(in_.width), kept = std::size_t(x1_ - x0_);
    for (int dy = -kRegressionRadius; dy <= kRegressionRadius; ++dy) {
      for (int dx = -kRegressionRadius; dx <= kRegressionRadius; ++dx) {
        const std::size_t base = slot(offset_index(dx, dy), ay);
        const int by = ay + dy;
        // The pixels ax whose partner ax + dx (in row by) is in the image.
        const int first = by >= 0 && by < in_.height ? std::min(x1_, std::max(x0_, -dx)) : x1_;
        const int end = std::max(first, std::min(x1_, in_.width - dx));
        const std::size_t from = std::size_t(first - x0_), to = std::size_t(end - x0_);
        std::fill(&terms_[base], &terms_[base] + from, 0.0);
        std::fill(&valid_[base], &valid_[base] + from, 0.0);
        if (end > first)
          patch_terms(planes_, std::size_t(ay) * image_width + std::size_t(first),
                      std::size_t(by) * image_width + std::size_t(first + dx),
                      std::size_t(end - first), &terms_[base + from], &valid_[base + from]);
        std::fill(&terms_[base] + to, &terms_[base] + kept, 0.0);
        std::fill(&valid_[base] + to, &valid_[base] + kept, 0.0);
      }
    }
  }

  const DenoiseInput& in_;
  const GuidePlanes& planes_;
  std::size_t width_;    // the columns a row of terms has room for
  int x0_ = 0, x1_ = 0;  // the columns kept: a tile's pixels and their patches'
  int next_row_ = 0;
  std::vector<double> terms_;  // [offset][row mod 3][x]
  std::vector<double> valid_;  // 1 where the term's two pixels are in the image, else 0
};

// Four neighbouring pixels of a row are fitted at once, one per vector lane (core/parallel/
// lanes.h), over the union of their windows: each lane's window is the union's columns that are
// its own, and a neighbour outside it, or of weight 0, enters as zeros, which add +0.0 and change
// no sum. Each lane so gathers its sums in its own window's order, to the bits one pixel fitted
// alone gets (1.3-1.5x faster than Eigen's fixed-size outer products a pixel at a time, which
// also summed the upper half).
constexpr int kUnionSide = 2 * kRegressionRadius + kLanes;
constexpr int kUnionRows = (2 * kRegressionRadius + 1) * kUnionSide;

// The union window's rows, lane by lane: the design (columns as above), the image's values and
// the distances (each lane's own, to its pixel), as the filter lays them out.
struct LaneRows {
  Lanes x[kUnionRows][kColumns];
  Lanes y[kUnionRows][3];
  Lanes distance[kUnionRows];
  bool inside[kUnionRows][kLanes];
  int rows = 0;
};

// One lane's normal equations: the lower half of the normal matrix, the right-hand sides (one a
// channel) and the weights' sum.
struct LaneSystems {
  Lanes normal[kColumns][kColumns];
  Lanes rhs[kColumns][3];
  Lanes total;
};

// Row A of the lower half of the normal matrix and of the right-hand sides: for each entry,
// (w x_A) x_b added in the rows' order. The entry is the outer loop, so that its lanes' sums
// stay in registers.
template <int A>
[[gnu::always_inline]] inline void gather_row_of_normal(const LaneRows& rows, const Lanes* w,
                                                        const int* active, int count,
                                                        LaneSystems& out) {
  Lanes normal[A + 1] = {}, rhs[3] = {};
  for (int i = 0; i < count; ++i) {
    const int r = active[i];
    const Lanes wx = w[r] * rows.x[r][A];
    for (int b = 0; b <= A; ++b) normal[b] += wx * rows.x[r][b];
    for (int c = 0; c < 3; ++c) rhs[c] += wx * rows.y[r][c];
  }
  for (int b = 0; b <= A; ++b) out.normal[A][b] = normal[b];
  for (int c = 0; c < 3; ++c) out.rhs[A][c] = rhs[c];
}

template <int... A>
[[gnu::always_inline]] inline void gather_rows_of_normal(const LaneRows& rows, const Lanes* w,
                                                         const int* active, int count,
                                                         LaneSystems& out,
                                                         std::integer_sequence<int, A...>) {
  (gather_row_of_normal<A>(rows, w, active, count, out), ...);
}

// The lanes' normal equations (lower halves: the Cholesky factorisation reads nothing else). A row
// of weight 0 in every lane adds +0.0 to every sum and is left out: listed once, not tested for
// each entry (a third of the second pass's rows, mispredicted).
RTIOW_DISPATCHED void gather_systems(const LaneRows& rows, const Lanes* w, LaneSystems& out) {
  int active[kUnionRows];
  int count = 0;
  for (int r = 0; r < rows.rows; ++r) {
    bool zero = true;
    for (int l = 0; l < kLanes; ++l) zero = zero && w[r][l] == 0.0;
    active[count] = r;
    count += zero ? 0 : 1;
  }
  gather_rows_of_normal(rows, w, active, count, out, std::make_integer_sequence<int, kColumns>());
  Lanes total = {};
  for (int r = 0; r < rows.rows; ++r) total += w[r];
  out.total = total;
}

// The weighted mean's sums alone (a Fit::kMean): the sum of w y, in the intercept's right-hand
// side, and the weights' sum; no normal matrix.
RTIOW_DISPATCHED void gather_means(const LaneRows& rows, const Lanes* w, LaneSystems& out) {
  Lanes rhs[3] = {}, total = {};
  for (int r = 0; r < rows.rows; ++r) {
    for (int c = 0; c < 3; ++c) rhs[c] += w[r] * rows.y[r][c];
    total += w[r];
  }
  for (int c = 0; c < 3; ++c) out.rhs[0][c] = rhs[c];
  out.total = total;
}

struct Regressed {
  Eigen::Vector3d value;
  double own_weight;
};

// Lane l's weighted least squares fit reaches its pixel through the first row of the inverse
// normal matrix (core/denoise/intercept_solve.h).
Eigen::Matrix<double, kColumns, 1> intercept_row(const LaneSystems& s, int l) {
  Normal normal = Normal::Zero();
  for (int a = 0; a < kColumns; ++a)
    for (int b = 0; b <= a; ++b) normal(a, b) = s.normal[a][b][l];
  for (int c = 1; c < kColumns; ++c) normal(c, c) += kRegressionRidge * s.total[l];
  return inverse_first_row(normal);
}

// Lane l's weighted mean at its pixel (whose own weight, at least that of its own row, keeps the
// sum above 0).
Regressed mean_lane(const LaneSystems& s, int l, double self_weight) {
  const double total = s.total[l];
  Regressed out{Eigen::Vector3d::Zero(), self_weight / total};
  for (int c = 0; c < 3; ++c) out.value[c] = s.rhs[0][c][l] / total;
  return out;
}

// Lane l's fit at its pixel, whose own weight is `self_weight`.
Regressed fit_lane(const Eigen::Matrix<double, kColumns, 1>& row, const LaneSystems& s, int l,
                   double self_weight) {
  Regressed out{Eigen::Vector3d::Zero(), self_weight * row(0)};
  for (int a = 0; a < kColumns; ++a)
    for (int c = 0; c < 3; ++c) out.value[c] += row(a) * s.rhs[a][c][l];
  return out;
}

// The union of the windows of the pixels (px0 .. px0 + kLanes - 1, py), clipped to the image.
struct UnionWindow {
  int x0, x1, y0, y1;  // inclusive
};

UnionWindow union_window(const DenoiseInput& in, int px0, int py) {
  return {std::max(0, px0 - kRegressionRadius),
          std::min(in.width - 1, px0 + kLanes - 1 + kRegressionRadius),
          std::max(0, py - kRegressionRadius), std::min(in.height - 1, py + kRegressionRadius)};
}

// The union window's rows, each lane's its own. A feature enters as its difference from the
// pixel's, on a scale of about one: albedo and normal as they are, depth relative to the larger
// of the two (0 where both are the sky). With `patches`, each lane's distances one at a time
// (where lay_out_lane_distances cannot take them), else 0.
RTIOW_DISPATCHED void lay_out_rows(const DenoiseInput& in, const std::vector<Color>& image,
                                   const UnionWindow& u, const PatchDistances* patches, int px0,
                                   int py, LaneRows& out, int* self) {
  Lanes own[FirstHitSum::kChannels], lane_x;
  for (int l = 0; l < kLanes; ++l) {
    const int px = std::min(px0 + l, in.width - 1);  // a lane past the edge is masked
    const PixelFeatures& f = in.features[std::size_t(py) * std::size_t(in.width) + std::size_t(px)];
    for (std::size_t c = 0; c < FirstHitSum::kChannels; ++c) own[c][l] = double(f[c]);
    lane_x[l] = double(px0 + l);
  }
  const std::size_t depth = FirstHitSum::kChannels - 1;
  int row = 0;
  for (int qy = u.y0; qy <= u.y1; ++qy) {
    const Lanes dy = Lanes{} + double(qy - py) / kRegressionRadius;
    for (int qx = u.x0; qx <= u.x1; ++qx, ++row) {
      const std::size_t q = std::size_t(qy) * std::size_t(in.width) + std::size_t(qx);
      LaneMask keep{};
      for (int l = 0; l < kLanes; ++l) {
        const int px = px0 + l;
        const bool inside = px < in.width && std::abs(qx - px) <= kRegressionRadius;
        keep[l] = inside ? -1 : 0;
        out.inside[row][l] = inside;
        if (qy == py && qx == px) self[l] = row;
      }
      const PixelFeatures& f = in.features[q];
      out.x[row][0] = Lanes(LaneMask(Lanes{} + 1.0) & keep);
      for (std::size_t c = 0; c < depth; ++c)
        out.x[row][1 + c] = Lanes(LaneMask((double(f[c]) - own[c])) & keep);
      // Depth: std::max(q, p) is q < p ? p : q.
      const Lanes qd = Lanes{} + double(f[depth]), pd = own[depth];
      const Lanes larger = qd < pd ? pd : qd;
      out.x[row][1 + depth] = Lanes(LaneMask(larger > 0 ? (qd - pd) / larger : Lanes{}) & keep);
      out.x[row][kColumns - 2] = Lanes(LaneMask((double(qx) - lane_x) / kRegressionRadius) & keep);
      out.x[row][kColumns - 1] = Lanes(LaneMask(dy) & keep);
      for (std::size_t c = 0; c < 3; ++c)
        out.y[row][c] = Lanes(LaneMask(Lanes{} + double(image[q][c])) & keep);
      Lanes distance{};
      if (patches)
        for (int l = 0; l < kLanes; ++l)
          if (keep[l]) distance[l] = patches->distance(px0 + l, py, qx - px0 - l, qy - py);
      out.distance[row] = distance;
    }
  }
  out.rows = row;
}

// The lanes' distances where their patches are whole (PatchDistances::lanes_inside): at one
// offset they are four neighbouring terms of each row of patch terms, so offset by offset,
// each lane's goes to the row of its neighbour at that offset.
RTIOW_DISPATCHED void lay_out_lane_distances(const PatchDistances& patches, const UnionWindow& u,
                                             int px0, int py, LaneRows& out) {
  const int union_width = u.x1 - u.x0 + 1;
  for (int dy = u.y0 - py; dy <= u.y1 - py; ++dy) {
    for (int dx = -kRegressionRadius; dx <= kRegressionRadius; ++dx) {
      Lanes distance;
      patches.distances(px0, py, dx, dy, distance);
      for (int l = 0; l < kLanes; ++l) {
        const int qx = px0 + l + dx;
        if (qx >= u.x0 && qx <= u.x1)
          out.distance[(py + dy - u.y0) * union_width + (qx - u.x0)][l] = distance[l];
      }
    }
  }
}

}  // namespace

std::vector<FilteredHalf> filter_half(const DenoiseInput& in, const std::vector<Color>& half,
                                      const Guide& guide, const std::vector<Weighting>& weightings,
                                      const DenoiseControl& control, int columns_per_tile) {
  if (!guide.image || !guide.variance)
    throw std::invalid_argument("filter_half: a guide and its variance");
  if (columns_per_tile < kLanes || columns_per_tile % kLanes != 0)
    throw std::invalid_argument("filter_half: columns per tile a positive multiple of the lanes");
  const std::size_t n = in.size();
  std::vector<FilteredHalf> out(weightings.size());
  for (FilteredHalf& f : out) f.color.resize(n), f.own_weight.resize(n);

  const GuidePlanes planes(guide, in.width, in.height);
  // Each thread's working memory, kept from chunk to chunk (fresh pages for every chunk cost
  // more time in the kernel than the patch terms in the loop).
  struct Scratch {
    std::unique_ptr<LaneRows> rows = std::make_unique<LaneRows>();
    std::unique_ptr<LaneSystems> systems = std::make_unique<LaneSystems>();
    std::unique_ptr<Lanes[]> w = std::make_unique<Lanes[]>(kUnionRows);
    std::optional<PatchDistances> patches;
  };
  tbb::enumerable_thread_specific<Scratch> scratch;
  // Tiles of a chunk of rows and at most columns_per_tile columns, so that each row's patch terms
  // serve the rows around it and stay in cache.
  const std::size_t chunks = (std::size_t(in.height) + kRowsPerChunk - 1) / kRowsPerChunk;
  const std::size_t tile = std::size_t(columns_per_tile);
  const std::size_t tiles = (std::size_t(in.width) + tile - 1) / tile;
  parallel_for_range(chunks * tiles, 1, [&](std::size_t first_task, std::size_t end_task) {
    for (std::size_t task = first_task; task < end_task; ++task) {
      const int y0 = int(task / tiles * kRowsPerChunk);
      const int y1 = std::min(in.height, y0 + int(kRowsPerChunk));
      const int x0 = int(task % tiles * tile);
      const int x1 = std::min(in.width, x0 + columns_per_tile);
      Scratch& local = scratch.local();
      LaneRows* const rows = local.rows.get();
      LaneSystems* const systems = local.systems.get();
      Lanes* const w = local.w.get();
      if (!local.patches) local.patches.emplace(in, planes, columns_per_tile);
      PatchDistances& patches = *local.patches;
      patches.restart(x0, x1);
      for (int py = y0; py < y1; ++py) {
        if (control.stop()) return;
        patches.at_row(py);
        for (int px0 = x0; px0 < x1; px0 += kLanes) {
          int self[kLanes] = {};
          const UnionWindow u = union_window(in, px0, py);
          const bool whole_patches = patches.lanes_inside(px0, py);
          lay_out_rows(in, half, u, whole_patches ? nullptr : &patches, px0, py, *rows, self);
          if (whole_patches) lay_out_lane_distances(patches, u, px0, py, *rows);
          for (std::size_t k = 0; k < weightings.size(); ++k) {
            const bool mean = weightings[k].fit == Fit::kMean;
            const double bandwidth = double(weightings[k].bandwidth);
            const double scale = 1.0 / (bandwidth * bandwidth);
            // Weights below e^-30 are 0: they change nothing, and as subnormal numbers they made
            // the products several times slower.
            for (int r = 0; r < rows->rows; ++r) {
              for (int l = 0; l < kLanes; ++l) {
                const double d = rows->distance[r][l] * scale;
                w[r][l] = !rows->inside[r][l] || d >= 30.0 ? 0.0 : d == 0.0 ? 1.0 : std::exp(-d);
              }
            }
            if (mean)
              gather_means(*rows, w, *systems);
            else
              gather_systems(*rows, w, *systems);
            for (int l = 0; l < kLanes && px0 + l < in.width; ++l) {
              const std::size_t p = std::size_t(py) * std::size_t(in.width) + std::size_t(px0 + l);
              const double self_weight = w[self[l]][l];
              const Regressed fitted =
                  mean ? mean_lane(*systems, l, self_weight)
                       : fit_lane(intercept_row(*systems, l), *systems, l, self_weight);
              out[k].color[p] = {float(fitted.value[0]), float(fitted.value[1]),
                                 float(fitted.value[2])};
              out[k].own_weight[p] = float(fitted.own_weight);
            }
          }
        }
        control.advance(std::uint64_t(x1 - x0));
      }
    }
  });
  return out;
}

}  // namespace rtiow
