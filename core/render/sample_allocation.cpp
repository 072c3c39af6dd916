#include "core/render/sample_allocation.h"

#include <algorithm>
#include <cmath>

#include "core/film/pixel_neighbours.h"
#include "core/film/pixel_variance.h"
#include "core/film/replicate_variance.h"
#include "core/parallel/parallel_for_range.h"

namespace rtiow {

// Pixels a parallel chunk takes: enough that a chunk outweighs its task.
inline constexpr std::size_t kPixelsPerChunk = 4096;

namespace {

// body(p) for every pixel index p < n, in parallel (each pixel's value its own: the same for
// any split).
template <typename PixelBody>
void for_each_pixel(std::size_t n, const PixelBody& body) {
  for_each_index(n, kPixelsPerChunk, body);
}

// Rows of the image in parallel, likewise.
template <typename RowBody>
void for_each_row(int height, const RowBody& row) {
  parallel_for_range(std::size_t(height), 8, [&](std::size_t begin, std::size_t end) {
    for (std::size_t y = begin; y < end; ++y) row(int(y));
  });
}

}  // namespace

std::vector<double> neighbourhood_mean(int width, int height, const std::vector<double>& own) {
  std::vector<double> pooled(own.size());
  for_each_row(height, [&](int y) {
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
  });
  return pooled;
}

std::vector<double> neighbourhood_median(int width, int height, const std::vector<double>& own) {
  std::vector<double> pooled(own.size());
  for_each_row(height, [&](int y) {
    std::vector<double> around;
    around.reserve(8);
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
  });
  return pooled;
}

std::vector<Vec3d> sampler_ratios(const RenderSettings& settings, const PixelSums& sums,
                                  const std::vector<std::uint32_t>& samples) {
  // The sampler's gain over independent samples, from each pixel's neighbours' replicates. One
  // sequence has no replicates: its sample variance serves as it is (it overstates a Sobol
  // mean's error, but a budget only weighs pixels against one another).
  return replicates(settings) > 1
             ? replicate_ratios(settings.width, settings.height, sums.color, sums.spreads, samples,
                                settings.first_sample, settings.sampler)
             : std::vector<Vec3d>(samples.size(), Vec3d(1, 1, 1));
}

std::vector<double> neighbourhood_relative_variance(const RenderSettings& settings,
                                                    const PixelSums& sums,
                                                    const std::vector<std::uint32_t>& samples,
                                                    Pooling pooling) {
  return neighbourhood_relative_variance(settings, sums, samples,
                                         sampler_ratios(settings, sums, samples), pooling);
}

std::vector<double> neighbourhood_relative_variance(const RenderSettings& settings,
                                                    const PixelSums& sums,
                                                    const std::vector<std::uint32_t>& samples,
                                                    const std::vector<Vec3d>& ratio,
                                                    Pooling pooling) {
  // Each pixel's relative variance per sample scaled to what its mean really has.
  std::vector<double> own(samples.size());
  for_each_pixel(own.size(), [&](std::size_t p) {
    own[p] = relative_sample_variance(sums.color[p], sums.spreads[p], samples[p], ratio[p]);
  });
  return pooling == Pooling::Median ? neighbourhood_median(settings.width, settings.height, own)
                                    : neighbourhood_mean(settings.width, settings.height, own);
}

std::vector<double> neighbourhood_relative_variance(const RenderSettings& settings,
                                                    const PixelAccumulators& pixels,
                                                    Pooling pooling) {
  return neighbourhood_relative_variance(settings, pixels.sums, pixels.samples, pooling);
}

PixelEstimates pooled_estimates(const RenderSettings& settings, const PixelAccumulators& pixels) {
  std::vector<double> cost(pixels.samples.size());
  for_each_pixel(cost.size(), [&](std::size_t p) {
    const std::uint32_t n = pixels.samples[p];
    cost[p] = n > 0 ? double(pixels.rays[p]) / double(n) : 1.0;
  });
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
  for_each_pixel(r.size(), [&](std::size_t p) { r[p] = std::sqrt(e.variance[p] / e.cost[p]); });
  return r;
}

// A pixel's count at scale k: round(k sqrt(v / c)), at least its current count, at most `most`.
std::uint32_t count_at(double ratio, std::uint32_t current, double k, std::uint32_t most) {
  const double ideal = std::round(k * ratio);
  const std::uint32_t capped = ideal >= double(most) ? most : std::uint32_t(ideal);
  return std::max(current, capped);
}

void counts_at(const std::vector<double>& ratio, const std::vector<std::uint32_t>& current,
               double k, std::uint32_t most, std::vector<std::uint32_t>& out) {
  for_each_pixel(current.size(),
                 [&](std::size_t p) { out[p] = count_at(ratio[p], current[p], k, most); });
}

// decide(sum(term(p) for p in [0, n)) / divisor), with the sum as the serial loop in index
// order rounds it, `decide` a comparison with `threshold`. In parallel: the chunks' sums, added
// in order, differ from the serial sum by less than 2 n u times the sum of magnitudes (u =
// 2^-53), so wherever the threshold is farther than that from their total the two decide alike;
// nearer (or not finite), the serial sum decides. The counts, and so the image, are the serial
// loop's.
template <typename Term, typename Decide>
bool decide_sum(std::size_t n, double divisor, double threshold, const Term& term,
                const Decide& decide) {
  const std::size_t chunks = (n + kPixelsPerChunk - 1) / kPixelsPerChunk;
  std::vector<double> sums(chunks), magnitudes(chunks);
  parallel_for_range(chunks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      double sum = 0, magnitude = 0;
      for (std::size_t p = c * kPixelsPerChunk; p < std::min(n, (c + 1) * kPixelsPerChunk); ++p) {
        const double t = term(p);
        sum += t, magnitude += std::abs(t);
      }
      sums[c] = sum, magnitudes[c] = magnitude;
    }
  });
  double total = 0, magnitude = 0;
  for (std::size_t c = 0; c < chunks; ++c) total += sums[c], magnitude += magnitudes[c];
  const double value = total / divisor;
  const double bound = (4.0 * double(n) + 4.0) * 0x1p-53 * magnitude / std::abs(divisor);
  if (std::isfinite(value) && std::isfinite(bound) && std::abs(value - threshold) > bound) {
    return decide(value);
  }
  double serial = 0;
  for (std::size_t p = 0; p < n; ++p) serial += term(p);
  return decide(serial / divisor);
}

// The scales bracketing where `past` starts to hold, to within 1e-7 relative: `past` is false
// at `below` (or `below` is the smallest scale, where no pixel moves) and true at `above` (or
// `above` is the largest, where every pixel is at `most`). Bisection on log k; `past(k)`
// judges the counts at scale k.
struct Bracket {
  double below, above;
};

template <typename Past>
Bracket bracket_scale(const std::vector<double>& ratio, std::uint32_t most, const Past& past) {
  double largest = 0, smallest = INFINITY;
  for (const double r : ratio) {
    if (r > 0 && std::isfinite(r)) largest = std::max(largest, r), smallest = std::min(smallest, r);
  }
  if (largest == 0) return {0, 0};  // no pixel has any variance: nothing to gain
  double lo = std::log(0.4 / largest), hi = std::log(2.0 * double(most) / smallest);
  if (!past(std::exp(hi))) return {std::exp(hi), std::exp(hi)};
  while (hi - lo > 1e-7) {
    const double mid = 0.5 * (lo + hi);
    (past(std::exp(mid)) ? hi : lo) = mid;
  }
  return {std::exp(lo), std::exp(hi)};
}

}  // namespace

std::vector<std::uint32_t> allocate_budget(const PixelEstimates& estimates,
                                           const std::vector<std::uint32_t>& current, double budget,
                                           std::uint32_t most) {
  const std::vector<double> ratio = ratios(estimates);
  const Bracket k = bracket_scale(ratio, most, [&](double scale) {
    return decide_sum(
        current.size(), 1.0, budget,
        [&](std::size_t p) {
          return double(count_at(ratio[p], current[p], scale, most)) * estimates.cost[p];
        },
        [&](double cost) { return cost > budget; });
  });
  std::vector<std::uint32_t> counts(current.size());
  counts_at(ratio, current, k.below, most, counts);  // the largest scale that fits
  return counts;
}

std::vector<std::uint32_t> allocate_for_error(const PixelEstimates& estimates,
                                              const std::vector<std::uint32_t>& current,
                                              double rel_mse, std::uint32_t most) {
  const std::vector<double> ratio = ratios(estimates);
  const Bracket k = bracket_scale(ratio, most, [&](double scale) {
    return decide_sum(
        current.size(), double(current.size()), rel_mse,
        [&](std::size_t p) {
          return estimates.variance[p] / double(count_at(ratio[p], current[p], scale, most));
        },
        [&](double error) { return error <= rel_mse; });
  });
  std::vector<std::uint32_t> counts(current.size());
  counts_at(ratio, current, k.above, most, counts);  // the smallest scale that reaches it
  return counts;
}

}  // namespace rtiow
