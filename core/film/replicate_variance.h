#pragma once
// The variance of each pixel's mean, honest for every sampler.
//
// A pixel's sample variance over n is the variance of its mean only for independent samples;
// for scrambled Sobol points the mean converges faster and that figure overstates the error
// several times (0.34 of it was delivered on the cover at 64 spp). A pixel's samples alternate
// between two independent replicates (core/sampling/sampler.h), so the squared difference of
// their means is an unbiased estimate of the variance of the pixel's mean whatever the sampler,
// but with one degree of freedom. The estimate used everywhere is therefore
//
//   variance(p) = 7/8 sample variance over n (p) * ratio(window around p, p left out)
//               + 1/8 replicate estimate (p),
//   ratio = sum of replicate estimates / sum of sample variances over n, over the window,
//           per channel, without the neighbours far noisier than p's own (kReplicateTrimFactor;
//           in an adaptive render, over the window's pixels of about the same count instead),
//
// which keeps each pixel's own shape (its sample variance, n - 1 degrees of freedom) and takes
// the sampler's gain over independent sampling from the replicates of its neighbours, where it
// has some hundred degrees of freedom; an eighth of the pixel's own replicate estimate (both
// are unbiased) brings in what the gain does differently at this pixel. It assumes that gain
// changes slowly across the image (measured: the ratio is near 0 in the sky and 0.2-0.5 on the
// ground), and is weakest where it does not. Where the neighbours hold no evidence (fewer than
// kReplicateMinNeighbours with any spread: a channel constant within most pixels, a small
// image) the ratio is 1, so a pixel whose samples differ never reports 0. The ratio is per channel:
// the gain differs between them (on the blue diffuse sphere of `materials` at 1024 spp one ratio
// for all three understated red's and green's variance 2.5x). docs/accuracy.md has the calibration
// measured against independent renders.

#include <cstdint>
#include <vector>

#include "core/film/pixel_variance.h"
#include "core/film/sample_sum.h"
#include "core/geometry/vec3.h"
#include "core/sampling/sampler.h"

namespace rtiow {

// The window is (2 kReplicateWindowRadius + 1)^2 pixels around the pixel, the pixel left out
// (so that an adaptive pixel's count never depends on its own samples through the ratio).
inline constexpr int kReplicateWindowRadius = 7;
// A ratio is taken only from at least this many neighbours with a spread (a constant pixel is
// no evidence of the gain); with fewer in the whole window the ratio is 1, the independent
// bound. In an adaptive render a pixel borrows the ratio from window neighbours whose count
// is within a factor of two of its own (the gain grows with the count) where this many are.
inline constexpr double kReplicateMinNeighbours = 32;

// In a render whose pixels share one count, a pixel's ratio comes from the window's neighbours
// of about its own level of noise, where at least kReplicateMinNeighbours of them are: a ratio
// of sums is dominated by its noisiest pixels, and the gain differs between kinds of noise.
// Left out above: neighbours whose sample variance is over kReplicateTrimFactor times the
// larger of p's 3x3 neighbours' mean level (p left out) and p's own. A sky pixel whose window
// reaches the spheres took their ratio, some hundred times its own, and overstated its
// variance 5-50x (padded-sobol on the cover at 1024 spp: per-pixel calibration 0.89); a smooth
// ground pixel took the ratio of neighbours noisy with rare paths (gain near 1), 0.77 on a
// ground lit by the sky at 16 spp. Left out below: neighbours under p's own over
// kReplicateQuietFactor. A pixel at an edge, among quiet sky, took the sky's ratio near 0 and
// reported z^2 of 6e4 (materials, padded-sobol, 64 spp). docs/accuracy.md has the measurements
// (2026-11-26): every sampler and scene 0.97-1.04 per pixel from 16 spp.
inline constexpr double kReplicateTrimFactor = 2;
inline constexpr double kReplicateQuietFactor = 16;

// The weight of a pixel's own replicate estimate in its variance (the rest is its sample
// variance scaled by its neighbours' ratio). Measured on cover, materials and defocus at 16,
// 64 and 1024 spp (docs/accuracy.md): with per-channel, trimmed ratios 1/8 keeps every case
// within 0.95-1.08 per pixel; 1/4 (chosen when one ratio served all channels) gives 1.09-1.10
// on materials at 1024 spp and the cover at 16 (one degree of freedom, a quarter of the
// estimate: E[1/estimate] grows), and 0 gives 1.10 on materials at 1024.
inline constexpr double kOwnReplicateWeight = 0.125;

// How many of the n samples from `first` have an odd index (the second replicate).
constexpr std::uint64_t odd_samples(std::uint64_t first, std::uint64_t n) {
  return (first + n) / 2 - first / 2;
}

// A pixel's replicate estimate of the variance of its mean, per channel: the squared
// difference of the replicates' means, weighted for unequal counts, n_even n_odd / n^2
// (1/4 for equal halves). 0 when one replicate is empty.
Vec3d replicate_estimate(const PixelSum& sum, const PixelSpread& spread, std::uint64_t first,
                         std::uint64_t n);

// Each pixel's ratio of honest to sample variance per channel (row major, width x height), from
// the pixels' sums, spreads and counts, all of which start at sample index `first`; 1 for the
// independent sampler.
std::vector<Vec3d> replicate_ratios(int width, int height, const std::vector<PixelSum>& sums,
                                    const std::vector<PixelSpread>& spreads,
                                    const std::vector<std::uint32_t>& samples, std::uint64_t first,
                                    SamplerKind sampler);

// The variance of each pixel's mean, per channel: its sample variance over n times its ratio,
// or, for the independent sampler, for which it is exact, the sample variance over n alone.
std::vector<Vec3d> honest_variances(int width, int height, const std::vector<PixelSum>& sums,
                                    const std::vector<PixelSpread>& spreads,
                                    const std::vector<std::uint32_t>& samples, std::uint64_t first,
                                    SamplerKind sampler);
// The same with the ratios replicate_ratios() gave for these very sums.
std::vector<Vec3d> honest_variances(const std::vector<Vec3d>& ratios,
                                    const std::vector<PixelSum>& sums,
                                    const std::vector<PixelSpread>& spreads,
                                    const std::vector<std::uint32_t>& samples, std::uint64_t first,
                                    SamplerKind sampler);

}  // namespace rtiow
