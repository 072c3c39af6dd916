#pragma once
// Where adaptive sampling spends samples. After n samples a pixel with relative variance v
// per sample adds v / n to the image's mean relMSE, and costs n c, c its rays per sample.
// For a given total cost the mean relMSE is smallest when n is proportional to sqrt(v / c)
// (set d/dn (v / n) = -lambda c). A rule that gives every pixel the same relative error
// (--target-error) makes n proportional to v instead: it spends on the noisiest pixels more
// than they return, which is why it does not beat uniform sampling at equal time.
//
// Every estimate a pixel is judged by is pooled from its 3x3 neighbours, itself left out: its
// own samples never decide how many samples it gets, so its mean stays unbiased.

#include <cstdint>
#include <vector>

#include "core/render/render_loop.h"

namespace rtiow {

// The mean of `own` over each pixel's neighbours in the 3x3 window, the pixel left out (a
// 1x1 image has none and keeps its own).
std::vector<double> neighbourhood_mean(int width, int height, const std::vector<double>& own);

// The median of `own` over the same neighbours (the mean of the middle two of an even count).
std::vector<double> neighbourhood_median(int width, int height, const std::vector<double>& own);

// How the neighbours' estimates are pooled. The mean is unbiased for the image's relMSE, which
// --image-error and --adaptive's allocation add up. The median is what a single pixel is
// judged by under --target-error: near an edge or a highlight the variance across the window
// is skewed, and the mean of the neighbours then sits above the typical pixel's own, which
// stopped the median pixel at 0.80-0.84 of the target on the cover (0.88-0.90 with the median;
// docs/accuracy.md).
enum class Pooling { Mean, Median };

// The relative variance per sample each pixel is judged by (pixel_variance.h), pooled.
std::vector<double> neighbourhood_relative_variance(const RenderSettings& settings,
                                                    const PixelAccumulators& pixels,
                                                    Pooling pooling = Pooling::Mean);
// The same from a film's sums and counts (a finished render's, a merge's).
std::vector<double> neighbourhood_relative_variance(const RenderSettings& settings,
                                                    const PixelSums& sums,
                                                    const std::vector<std::uint32_t>& samples,
                                                    Pooling pooling = Pooling::Mean);
// The same with each pixel's ratio of honest to sample variance given (replicate_ratios()'s for
// these sums, or 1s for one sequence).
std::vector<double> neighbourhood_relative_variance(const RenderSettings& settings,
                                                    const PixelSums& sums,
                                                    const std::vector<std::uint32_t>& samples,
                                                    const std::vector<Vec3d>& ratio,
                                                    Pooling pooling = Pooling::Mean);
// The ratios neighbourhood_relative_variance() takes for these sums.
std::vector<Vec3d> sampler_ratios(const RenderSettings& settings, const PixelSums& sums,
                                  const std::vector<std::uint32_t>& samples);

struct PixelEstimates {
  std::vector<double> variance;  // relative variance per sample, pooled
  std::vector<double> cost;      // rays per sample, pooled (at least 1)
};

PixelEstimates pooled_estimates(const RenderSettings& settings, const PixelAccumulators& pixels);

// The image's estimated mean relMSE with these counts: the mean of v / n.
double estimated_rel_mse(const std::vector<double>& variance,
                         const std::vector<std::uint32_t>& samples);

// The estimated cost (rays) of these counts: the sum of n c.
double estimated_cost(const std::vector<double>& cost, const std::vector<std::uint32_t>& samples);

// Counts proportional to sqrt(v / c) where that is above a pixel's current count (samples are
// never taken back) and at most `most`, as many as `budget` (estimated rays, counting those
// already spent) pays for; every pixel at `most` if the budget is larger.
std::vector<std::uint32_t> allocate_budget(const PixelEstimates& estimates,
                                           const std::vector<std::uint32_t>& current, double budget,
                                           std::uint32_t most);

// The cheapest such counts whose estimated mean relMSE is at most `rel_mse`; where that needs
// more than `most` somewhere, the counts at the largest scale the cap allows.
std::vector<std::uint32_t> allocate_for_error(const PixelEstimates& estimates,
                                              const std::vector<std::uint32_t>& current,
                                              double rel_mse, std::uint32_t most);

}  // namespace rtiow
