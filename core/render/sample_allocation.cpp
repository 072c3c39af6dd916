#include "core/render/sample_allocation.h"

#include <algorithm>
#include <cmath>

#include "core/film/pixel_neighbours.h"
#include "core/film/pixel_variance.h"
#include "core/film/replicate_variance.h"

namespace rtiow {

std::vector<double> neighbourhood_mean(int width, int height, const std::vector<double>& own) {
  std::vector<double> pooled(own.size());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      double total = 0;
      int count = 0;
      for_each_neighbour(width, height, x, y, [&](std::size_t q) {
        total += own[q];
        ++count;
      });
      const std::size_t p = std::size_t(y) * std::size_t(width) + std::size_t(x);
      pooled[p] = count > 0 ? total / count : own[p];
    }
  }
  return pooled;
}

std::vector<double> neighbourhood_median(int width, int height, const std::vector<double>& own) {
  std::vector<double> pooled(own.size());
  std::vector<double> around;
  around.reserve(8);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      around.clear();
      for_each_neighbour(width, height, x, y, [&](std::size_t q) { around.push_back(own[q]); });
      const std::size_t p = std::size_t(y) * std::size_t(width) + std::size_t(x);
      if (around.empty()) {
        pooled[p] = own[p];
        continue;
      }
      std::sort(around.begin(), around.end());
      const std::size_t m = around.size();
      pooled[p] = m % 2 == 1 ? around[m / 2] : 0.5 * (around[m / 2 - 1] + around[m / 2]);
    }
  }
  return pooled;
}

std::vector<double> neighbourhood_relative_variance(const RenderSettings& settings,
                                                    const PixelAccumulators& pixels,
                                                    Pooling pooling) {
  // Each pixel's relative variance per sample scaled to what its mean really has: the
  // sampler's gain over independent samples, from its neighbours' replicates. One sequence has
  // no replicates: its sample variance serves as it is (it overstates a Sobol mean's error, but
  // a budget only weighs pixels against one another).
  const std::vector<Vec3d> ratio =
      replicates(settings) > 1
          ? replicate_ratios(settings.width, settings.height, pixels.sums, pixels.spreads,
                             pixels.samples, settings.first_sample, settings.sampler)
          : std::vector<Vec3d>(pixels.samples.size(), Vec3d(1, 1, 1));
  std::vector<double> own(pixels.samples.size());
  for (std::size_t p = 0; p < own.size(); ++p) {
    own[p] =
        relative_sample_variance(pixels.sums[p], pixels.spreads[p], pixels.samples[p], ratio[p]);
  }
  return pooling == Pooling::Median ? neighbourhood_median(settings.width, settings.height, own)
                                    : neighbourhood_mean(settings.width, settings.height, own);
}

PixelEstimates pooled_estimates(const RenderSettings& settings, const PixelAccumulators& pixels) {
  std::vector<double> cost(pixels.samples.size());
  for (std::size_t p = 0; p < cost.size(); ++p) {
    const std::uint32_t n = pixels.samples[p];
    cost[p] = n > 0 ? double(pixels.rays[p]) / double(n) : 1.0;
  }
  PixelEstimates e{neighbourhood_relative_variance(settings, pixels),
                   neighbourhood_mean(settings.width, settings.height, cost)};
  // Every sample costs at least its set-up (a depth-0 or untraceable sample traces nothing).
  for (double& c : e.cost) c = std::max(c, 1.0);
  return e;
}

double estimated_rel_mse(const std::vector<double>& variance,
                         const std::vector<std::uint32_t>& samples) {
  double total = 0;
  for (std::size_t p = 0; p < samples.size(); ++p) total += variance[p] / double(samples[p]);
  return total / double(samples.size());
}

double estimated_cost(const std::vector<double>& cost, const std::vector<std::uint32_t>& samples) {
  double total = 0;
  for (std::size_t p = 0; p < samples.size(); ++p) total += double(samples[p]) * cost[p];
  return total;
}

namespace {

// Each pixel's sqrt(v / c): its count per unit of scale.
std::vector<double> ratios(const PixelEstimates& e) {
  std::vector<double> r(e.variance.size());
  for (std::size_t p = 0; p < r.size(); ++p) r[p] = std::sqrt(e.variance[p] / e.cost[p]);
  return r;
}

// The counts at scale k: round(k sqrt(v / c)), at least the current count, at most `most`.
void counts_at(const std::vector<double>& ratio, const std::vector<std::uint32_t>& current,
               double k, std::uint32_t most, std::vector<std::uint32_t>& out) {
  for (std::size_t p = 0; p < current.size(); ++p) {
    const double ideal = std::round(k * ratio[p]);
    const std::uint32_t capped = ideal >= double(most) ? most : std::uint32_t(ideal);
    out[p] = std::max(current[p], capped);
  }
}

// The scales bracketing where `past` starts to hold, to within 1e-7 relative: `past` is false
// at `below` (or `below` is the smallest scale, where no pixel moves) and true at `above` (or
// `above` is the largest, where every pixel is at `most`). Bisection on log k.
struct Bracket {
  double below, above;
};

template <typename Past>
Bracket bracket_scale(const std::vector<double>& ratio, const std::vector<std::uint32_t>& current,
                      std::uint32_t most, const Past& past) {
  double largest = 0, smallest = INFINITY;
  for (const double r : ratio) {
    if (r > 0 && std::isfinite(r)) largest = std::max(largest, r), smallest = std::min(smallest, r);
  }
  if (largest == 0) return {0, 0};  // no pixel has any variance: nothing to gain
  double lo = std::log(0.4 / largest), hi = std::log(2.0 * double(most) / smallest);
  std::vector<std::uint32_t> counts(current.size());
  counts_at(ratio, current, std::exp(hi), most, counts);
  if (!past(counts)) return {std::exp(hi), std::exp(hi)};
  while (hi - lo > 1e-7) {
    const double mid = 0.5 * (lo + hi);
    counts_at(ratio, current, std::exp(mid), most, counts);
    (past(counts) ? hi : lo) = mid;
  }
  return {std::exp(lo), std::exp(hi)};
}

}  // namespace

std::vector<std::uint32_t> allocate_budget(const PixelEstimates& estimates,
                                           const std::vector<std::uint32_t>& current, double budget,
                                           std::uint32_t most) {
  const std::vector<double> ratio = ratios(estimates);
  const Bracket k = bracket_scale(ratio, current, most, [&](const auto& n) {
    return estimated_cost(estimates.cost, n) > budget;
  });
  std::vector<std::uint32_t> counts(current.size());
  counts_at(ratio, current, k.below, most, counts);  // the largest scale that fits
  return counts;
}

std::vector<std::uint32_t> allocate_for_error(const PixelEstimates& estimates,
                                              const std::vector<std::uint32_t>& current,
                                              double rel_mse, std::uint32_t most) {
  const std::vector<double> ratio = ratios(estimates);
  const Bracket k = bracket_scale(ratio, current, most, [&](const auto& n) {
    return estimated_rel_mse(estimates.variance, n) <= rel_mse;
  });
  std::vector<std::uint32_t> counts(current.size());
  counts_at(ratio, current, k.above, most, counts);  // the smallest scale that reaches it
  return counts;
}

}  // namespace rtiow
