// Where adaptive sampling puts samples: in proportion to sqrt(variance / cost), never below a
// pixel's count, within the budget or just reaching the error asked for, and with a lower
// estimated error for its cost than uniform counts or counts proportional to the variance.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/render/sample_allocation.h"
#include "core/sampling/rng.h"

namespace rtiow {
namespace {

double total_cost(const PixelEstimates& e, const std::vector<std::uint32_t>& n) {
  return estimated_cost(e.cost, n);
}

// The allocation as a serial loop computes it: the bisection on log k, each scale judged by the
// sum of its counts' costs (or errors) in pixel order. The renderer judges the sums in parallel
// and must decide every scale as this does, or the images would change.
struct SerialAllocation {
  const PixelEstimates& e;
  const std::vector<std::uint32_t>& current;
  std::uint32_t most;

  std::vector<std::uint32_t> counts(double k) const {
    std::vector<std::uint32_t> n(current.size());
    for (std::size_t p = 0; p < n.size(); ++p) {
      const double ideal = std::round(k * std::sqrt(e.variance[p] / e.cost[p]));
      n[p] = std::max(current[p], ideal >= double(most) ? most : std::uint32_t(ideal));
    }
    return n;
  }
  template <typename Past>
  std::pair<double, double> bracket(const Past& past) const {
    double largest = 0, smallest = INFINITY;
    for (std::size_t p = 0; p < current.size(); ++p) {
      const double r = std::sqrt(e.variance[p] / e.cost[p]);
      if (r > 0 && std::isfinite(r))
        largest = std::max(largest, r), smallest = std::min(smallest, r);
    }
    double lo = std::log(0.4 / largest), hi = std::log(2.0 * double(most) / smallest);
    if (!past(counts(std::exp(hi)))) return {std::exp(hi), std::exp(hi)};
    while (hi - lo > 1e-7) {
      const double mid = 0.5 * (lo + hi);
      (past(counts(std::exp(mid))) ? hi : lo) = mid;
    }
    return {std::exp(lo), std::exp(hi)};
  }
  std::vector<std::uint32_t> for_budget(double budget) const {
    return counts(bracket([&](const auto& n) { return estimated_cost(e.cost, n) > budget; }).first);
  }
  std::vector<std::uint32_t> for_error(double goal) const {
    return counts(
        bracket([&](const auto& n) { return estimated_rel_mse(e.variance, n) <= goal; }).second);
  }
};

TEST(SampleAllocation, DecidesEveryScaleAsTheSerialSumDoes) {
  // A large image of skewed estimates (many chunks of the parallel sums), and budgets and goals
  // that are exactly what some counts cost or reach, so that the parallel sums' bound cannot
  // decide and the serial sum must.
  Pcg32 rng;
  rng.set_sequence(7, 11);
  const std::size_t n = 100003;
  PixelEstimates e{std::vector<double>(n), std::vector<double>(n)};
  std::vector<std::uint32_t> current(n);
  for (std::size_t p = 0; p < n; ++p) {
    const double u = rng.next_float();
    e.variance[p] = p % 97 == 0 ? 0.0 : 1e-3 / (1e-3 + u * u * u);
    e.cost[p] = 1.0 + 9.0 * rng.next_float();
    current[p] = 16 + (p % 5 == 0 ? 16 : 0);
  }
  const std::uint32_t most = 4096;
  const SerialAllocation serial{e, current, most};
  std::vector<double> budgets{estimated_cost(e.cost, current) * 1.5,
                              estimated_cost(e.cost, current) * 4.0};
  std::vector<double> goals{estimated_rel_mse(e.variance, current) / 3.0};
  for (const double k : {5.0, 40.0, 300.0}) {
    budgets.push_back(estimated_cost(e.cost, serial.counts(k)));  // exactly a scale's cost
    goals.push_back(estimated_rel_mse(e.variance, serial.counts(k)));
  }
  for (const double budget : budgets) {
    EXPECT_EQ(allocate_budget(e, current, budget, most), serial.for_budget(budget)) << budget;
  }
  for (const double goal : goals) {
    EXPECT_EQ(allocate_for_error(e, current, goal, most), serial.for_error(goal)) << goal;
  }
}

TEST(SampleAllocation, CountsFollowTheSquareRootOfVarianceOverCost) {
  // Variance 1, 4, 16 at cost 1, then variance 16 at cost 4: sqrt(v / c) = 1, 2, 4, 2.
  const PixelEstimates e{{1, 4, 16, 16}, {1, 1, 1, 4}};
  const std::vector<std::uint32_t> current(4, 2);
  const std::vector<std::uint32_t> n = allocate_budget(e, current, 20000, 1u << 20);
  EXPECT_LE(total_cost(e, n), 20000);
  EXPECT_GT(total_cost(e, n), 19990) << "the budget is spent, up to rounding";
  EXPECT_NEAR(double(n[1]) / n[0], 2.0, 0.01);
  EXPECT_NEAR(double(n[2]) / n[0], 4.0, 0.01);
  EXPECT_NEAR(double(n[3]) / n[0], 2.0, 0.01) << "four times the cost halves the share";
}

TEST(SampleAllocation, NeverTakesSamplesBackAndStopsAtTheCap) {
  const PixelEstimates e{{1, 1, 100, 0}, {1, 1, 1, 1}};
  const std::vector<std::uint32_t> current{500, 2, 2, 2};
  const std::vector<std::uint32_t> n = allocate_budget(e, current, 1000, 300);
  EXPECT_EQ(n[0], 500u) << "a pixel past its share keeps its samples";
  EXPECT_EQ(n[2], 300u) << "the noisiest pixel stops at the cap";
  EXPECT_EQ(n[3], 2u) << "a pixel without variance gains nothing";
  EXPECT_GT(n[1], 2u);
  // A budget smaller than what is spent moves nothing; a huge one puts every pixel that
  // gains anything at the cap.
  EXPECT_EQ(allocate_budget(e, current, 10, 300), current);
  EXPECT_EQ(allocate_budget(e, current, 1e12, 300), (std::vector<std::uint32_t>{500, 300, 300, 2}));
}

TEST(SampleAllocation, ReachesTheErrorAskedForAtTheLeastScale) {
  const PixelEstimates e{{0.5, 2, 8, 0.1, 30}, {1, 2, 3, 1, 5}};
  const std::vector<std::uint32_t> current(5, 16);
  for (const double goal : {1e-2, 1e-3, 1e-4}) {
    const std::vector<std::uint32_t> n = allocate_for_error(e, current, goal, 1u << 24);
    EXPECT_LE(estimated_rel_mse(e.variance, n), goal);
    // One sample fewer on the pixel that gains most per ray would miss the goal, or be at the
    // minimum: the counts are (up to rounding) the cheapest that reach it.
    std::vector<std::uint32_t> fewer = n;
    for (std::uint32_t& c : fewer) c = c > 16 ? std::uint32_t(std::floor(c * 0.99)) : c;
    EXPECT_GT(estimated_rel_mse(e.variance, fewer), goal) << goal;
  }
}

// The point of the rule: for the same estimated cost, sqrt(v / c) counts give a lower
// estimated mean relMSE than uniform counts and than counts proportional to v (what a rule
// that equalises every pixel's error does).
TEST(SampleAllocation, BeatsUniformAndProportionalToVarianceAtEqualCost) {
  Pcg32 rng(3, 4);
  PixelEstimates e;
  for (int p = 0; p < 1000; ++p) {
    const double u = rng.next_double();
    e.variance.push_back(std::exp(6 * u - 3));            // spread over e^-3..e^3
    e.cost.push_back(1 + 4 * rng.next_double() + 2 * u);  // costlier where noisier
  }
  const std::vector<std::uint32_t> start(e.variance.size(), 1);
  const std::vector<std::uint32_t> uniform(e.variance.size(), 64);
  const double budget = total_cost(e, uniform);
  const std::vector<std::uint32_t> best = allocate_budget(e, start, budget, 1u << 24);
  std::vector<std::uint32_t> by_variance(e.variance.size());
  double scale = 0;
  for (std::size_t p = 0; p < e.variance.size(); ++p) scale += e.variance[p] * e.cost[p];
  for (std::size_t p = 0; p < e.variance.size(); ++p) {
    by_variance[p] = std::max(1u, std::uint32_t(std::lround(budget * e.variance[p] / scale)));
  }
  const double best_error = estimated_rel_mse(e.variance, best);
  EXPECT_LE(total_cost(e, best), budget);
  EXPECT_LT(best_error * 1.2, estimated_rel_mse(e.variance, uniform));
  EXPECT_LT(best_error * 1.2,
            estimated_rel_mse(e.variance, by_variance) * total_cost(e, by_variance) / budget);
}

TEST(SampleAllocation, NeighbourhoodMeanLeavesThePixelOut) {
  // 3x3 with 9 at the centre: the centre sees only its neighbours (all 1); a corner sees its
  // three neighbours, the centre among them: (1 + 1 + 9) / 3.
  const std::vector<double> own{1, 1, 1, 1, 9, 1, 1, 1, 1};
  const std::vector<double> pooled = neighbourhood_mean(3, 3, own);
  EXPECT_DOUBLE_EQ(pooled[4], 1.0);
  EXPECT_DOUBLE_EQ(pooled[0], 11.0 / 3.0);
  EXPECT_DOUBLE_EQ(pooled[1], (1 + 1 + 1 + 1 + 9) / 5.0);
  EXPECT_EQ(neighbourhood_mean(1, 1, {7}), std::vector<double>{7}) << "no neighbours: its own";
}

TEST(SampleAllocation, NeighbourhoodMedianLeavesThePixelOutAndIgnoresOneNoisyNeighbour) {
  // One noisy neighbour (90) beside the centre: the mean of the centre's neighbours moves to
  // 12.25, their median stays at the typical pixel's 1 (even count: the middle two's mean).
  const std::vector<double> own{1, 1, 1, 90, 50, 1, 1, 1, 1};
  const std::vector<double> pooled = neighbourhood_median(3, 3, own);
  EXPECT_DOUBLE_EQ(neighbourhood_mean(3, 3, own)[4], 97.0 / 8.0);
  EXPECT_DOUBLE_EQ(pooled[4], 1.0);
  // A corner's three neighbours {1, 90, 50}: the middle one.
  EXPECT_DOUBLE_EQ(pooled[0], 50.0);
  // The top edge's middle pixel has five {1, 1, 90, 50, 1}.
  EXPECT_DOUBLE_EQ(pooled[1], 1.0);
  // The left edge's middle (90 itself) has {1, 1, 50, 1, 1}.
  EXPECT_DOUBLE_EQ(pooled[3], 1.0);
  EXPECT_EQ(neighbourhood_median(1, 1, {7}), std::vector<double>{7}) << "no neighbours: its own";
  // Two neighbours: their mean.
  EXPECT_EQ(neighbourhood_median(2, 1, {3, 5}), (std::vector<double>{5, 3}));
}

}  // namespace
}  // namespace rtiow
