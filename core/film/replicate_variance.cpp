#include "core/film/replicate_variance.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

#include "core/film/pixel_neighbours.h"
#include "core/film/window_sums.h"
#include "core/parallel/instruction_sets.h"
#include "core/parallel/lanes.h"
#include "core/parallel/parallel_for_range.h"

namespace rtiow {

Vec3d replicate_estimate(const PixelSum& sum, const PixelSpread& spread, std::uint64_t first,
                         std::uint64_t n) {
  const std::uint64_t odd = odd_samples(first, n), even = n - odd;
  if (odd == 0 || even == 0) return {0, 0, 0};
  const double weight = double(even) * double(odd) / (double(n) * double(n));
  double v[3];
  for (int c = 0; c < 3; ++c) {
    const double odd_sum = double(spread.odd.channel(c)) / PixelSum::kScale;
    const double even_sum = double(sum.channel(c) - spread.odd.channel(c)) / PixelSum::kScale;
    const double difference = even_sum / double(even) - odd_sum / double(odd);
    v[c] = weight * difference * difference;
  }
  return {v[0], v[1], v[2]};
}

namespace {

// Pixels one task of the per-pixel loops below takes.
inline constexpr std::size_t kPixelsPerTask = 4096;

// body(p) for every pixel index p < n, in parallel: each pixel's value is its own.
template <typename Body>
void for_each_pixel(std::size_t n, const Body& body) {
  for_each_index(n, kPixelsPerTask, body);
}

// A pixel's count class: the sampler's gain grows with the count, so an adaptive render's
// pixels borrow the ratio only from neighbours of about their own count (within 2x).
int count_class(std::uint32_t n) {
  return n < 2 ? -1 : std::bit_width(n) - 1;
}

// What a window holds of one channel: the sum of its pixels' replicate and sample estimates and
// how many pixels gave them (those with a spread).
struct WindowTotal {
  double replicate = 0, sample = 0, pixels = 0;
  WindowTotal operator+(const WindowTotal& o) const {
    return {replicate + o.replicate, sample + o.sample, pixels + o.pixels};
  }
  WindowTotal operator-(const WindowTotal& o) const {
    return {replicate - o.replicate, sample - o.sample, pixels - o.pixels};
  }
};

// The window totals of one count class (or of every class, `only` < 0) of one channel, the
// pixel itself left out. Its buffers are kept from call to call: an adaptive render takes a
// channel's windows once for every class, and fresh pages for each took most of its time.
class ClassWindows {
 public:
  const std::vector<WindowTotal>& of(int width, int height, const std::vector<Vec3d>& replicate,
                                     const std::vector<Vec3d>& sample, std::size_t channel,
                                     const std::vector<int>& classes, int only) {
    own_.resize(replicate.size());
    for_each_pixel(own_.size(), [&](std::size_t p) {
      if (classes[p] < 0 || (only >= 0 && classes[p] != only)) {
        own_[p] = {};
        return;
      }
      const double spread = sample[p][channel];
      own_[p] = {replicate[p][channel], spread, spread > 0.0 ? 1.0 : 0.0};
    });
    window_sums(own_, width, height, kReplicateWindowRadius, table_, totals_);
    for_each_pixel(own_.size(), [&](std::size_t p) { totals_[p] = totals_[p] - own_[p]; });
    return totals_;
  }

 private:
  std::vector<WindowTotal> own_, table_, totals_;
};

// Rounding of the windows' sums can leave a tiny negative remainder.
double ratio_of(double replicate, double sample) {
  return std::max(0.0, replicate) / sample;
}

// The ratio of a window's sums where at least kReplicateMinNeighbours of its pixels have a
// spread (a constant pixel adds nothing to either sum, so it is no evidence of the sampler's
// gain); with fewer, the neighbours say nothing about it, and the ratio is 1: the pixel's
// sample variance stands, the honest bound for independent samples. A handful of neighbours
// (or none but rounding, once) would make a ratio of a few degrees of freedom, near 0 by
// chance, and report next to no variance at a noisy pixel.
double ratio_of_window(double replicate, double sample, double pixels_with_spread) {
  return pixels_with_spread >= kReplicateMinNeighbours ? ratio_of(replicate, sample) : 1.0;
}

// The mean of one channel's sample variance over p's 3x3 neighbours, p left out (0 when none
// has one): what p's own level of noise is judged by, without p's own samples.
double neighbours_sample_variance(int width, int height, const std::vector<Vec3d>& sample,
                                  const std::vector<int>& classes, std::size_t channel, int x,
                                  int y) {
  double total = 0;
  int count = 0;
  for_each_neighbour(width, height, x, y, [&](std::size_t q) {
    if (classes[q] < 0) return;
    total += sample[q][channel];
    ++count;
  });
  return count > 0 ? total / count : 0.0;
}

// Which neighbours one channel of a pixel's window keeps: those whose sample variance lies in
// [low, limit] and is not 0 (as a constant or sampleless pixel's is), added in the window's
// order, row by row.
struct TrimmedBounds {
  double limit = 0, low = 0;
};

// Four pixels side by side, one per lane (core/parallel/lanes.h): each lane adds its own window
// in the same order as one pixel at a time, so every lane's sums are the scalar sums' bits
// (adding +0.0, the bits of a masked-out neighbour, leaves a sum as it is).

// The pixels (x .. x + 3, y) of one channel, each window whole inside the image. Compiled for
// each instruction set the hot loops pick from (AVX2's four lanes at once, else two and two).
RTIOW_DISPATCHED void trimmed_lanes(int width, const std::vector<double>& replicate,
                                    const std::vector<double>& sample,
                                    const TrimmedBounds (&bounds)[kLanes], int x, int y,
                                    double (&replicates)[kLanes], double (&samples)[kLanes],
                                    double (&kept)[kLanes]) {
  const int r = kReplicateWindowRadius;
  Lanes limit, low;
  for (int i = 0; i < kLanes; ++i) limit[i] = bounds[i].limit, low[i] = bounds[i].low;
  Lanes sum_replicate{}, sum_sample{}, count{};
  const Lanes one = {1, 1, 1, 1}, zero{};
  for (int ny = y - r; ny <= y + r; ++ny) {
    const std::size_t row = std::size_t(ny) * std::size_t(width) + std::size_t(x - r);
    for (int dx = 0; dx <= 2 * r; ++dx) {
      if (ny == y && dx == r) continue;  // each lane's own pixel
      Lanes spread, value;
      std::memcpy(&spread, &sample[row + std::size_t(dx)], sizeof spread);
      std::memcpy(&value, &replicate[row + std::size_t(dx)], sizeof value);
      const LaneMask keep = (spread <= limit) & (spread >= low) & (spread != zero);
      sum_replicate += Lanes(LaneMask(value) & keep);
      sum_sample += Lanes(LaneMask(spread) & keep);
      count += Lanes(LaneMask(one) & keep);
    }
  }
  for (int i = 0; i < kLanes; ++i)
    replicates[i] = sum_replicate[i], samples[i] = sum_sample[i], kept[i] = count[i];
}

// One pixel of one channel, its window clipped to the image.
void trimmed_pixel(int width, int height, const std::vector<double>& replicate,
                   const std::vector<double>& sample, const TrimmedBounds& bounds, int x, int y,
                   double& replicates, double& samples, double& kept) {
  const int r = kReplicateWindowRadius;
  replicates = samples = kept = 0;
  for (int ny = std::max(0, y - r); ny <= std::min(height - 1, y + r); ++ny) {
    for (int nx = std::max(0, x - r); nx <= std::min(width - 1, x + r); ++nx) {
      if (nx == x && ny == y) continue;
      const std::size_t q = std::size_t(ny) * std::size_t(width) + std::size_t(nx);
      const double spread = sample[q];
      if (spread > bounds.limit || spread < bounds.low || spread == 0.0) continue;
      replicates += replicate[q], samples += spread, kept += 1;
    }
  }
}

// For a render whose pixels all have one count: each pixel's ratio over the window's
// neighbours of about its own level of noise (at most kReplicateTrimFactor times the larger of
// its 3x3 neighbours' level and its own, at least its own over kReplicateQuietFactor), where at
// least kReplicateMinNeighbours remain (else the whole window's, already in `ratios`). Each
// channel's values laid out on their own, four pixels at a time where their windows are whole.
void trimmed_ratios(int width, int height, const std::vector<Vec3d>& replicate,
                    const std::vector<Vec3d>& sample, const std::vector<int>& classes,
                    std::vector<Vec3d>& ratios) {
  const int r = kReplicateWindowRadius;
  std::vector<double> channel_replicate[3], channel_sample[3];
  for (std::size_t c = 0; c < 3; ++c) {
    channel_replicate[c].resize(sample.size()), channel_sample[c].resize(sample.size());
    for_each_pixel(sample.size(), [&](std::size_t p) {
      // A pixel without an estimate has none of either (its sample variance 0 keeps it out).
      channel_replicate[c][p] = classes[p] < 0 ? 0.0 : replicate[p][c];
      channel_sample[c][p] = classes[p] < 0 ? 0.0 : sample[p][c];
    });
  }
  const auto bounds_of = [&](std::size_t c, int x, int y) {
    const std::size_t p = std::size_t(y) * std::size_t(width) + std::size_t(x);
    const double own = sample[p][c];
    const double level = neighbours_sample_variance(width, height, sample, classes, c, x, y);
    return TrimmedBounds{kReplicateTrimFactor * std::max(level, own), own / kReplicateQuietFactor};
  };
  const auto store = [&](std::size_t c, int x, int y, double replicates, double samples,
                         double kept) {
    const std::size_t p = std::size_t(y) * std::size_t(width) + std::size_t(x);
    if (classes[p] >= 0 && kept >= kReplicateMinNeighbours)
      ratios[p][c] = ratio_of(replicates, samples);
  };
  parallel_for_range(std::size_t(height), 1, [&](std::size_t row_begin, std::size_t row_end) {
    for (auto y = int(row_begin); y < int(row_end); ++y) {
      const bool rows_whole = y >= r && y + r < height;
      for (std::size_t c = 0; c < 3; ++c) {
        const std::vector<double>& rep = channel_replicate[c];
        const std::vector<double>& smp = channel_sample[c];
        int x = 0;
        while (x < width) {
          if (rows_whole && x >= r && x + kLanes - 1 + r < width) {
            TrimmedBounds bounds[kLanes];
            for (int i = 0; i < kLanes; ++i) bounds[i] = bounds_of(c, x + i, y);
            double replicates[kLanes], samples[kLanes], kept[kLanes];
            trimmed_lanes(width, rep, smp, bounds, x, y, replicates, samples, kept);
            for (int i = 0; i < kLanes; ++i) store(c, x + i, y, replicates[i], samples[i], kept[i]);
            x += kLanes;
            continue;
          }
          double replicates = 0, samples = 0, kept = 0;
          trimmed_pixel(width, height, rep, smp, bounds_of(c, x, y), x, y, replicates, samples,
                        kept);
          store(c, x, y, replicates, samples, kept);
          ++x;
        }
      }
    }
  });
}

}  // namespace

std::vector<Vec3d> replicate_ratios(int width, int height, const std::vector<PixelSum>& sums,
                                    const std::vector<PixelSpread>& spreads,
                                    const std::vector<std::uint32_t>& samples, std::uint64_t first,
                                    SamplerKind sampler) {
  if (sampler == SamplerKind::Independent) return std::vector<Vec3d>(sums.size(), Vec3d{1, 1, 1});
  std::vector<Vec3d> replicate(sums.size()), sample(sums.size());
  std::vector<int> classes(sums.size(), -1);
  for_each_pixel(sums.size(), [&](std::size_t p) {
    if (samples[p] < 2) return;  // no estimate of either kind
    const Vec3d own = variance_of_mean(sums[p], spreads[p], samples[p]);
    if (!std::isfinite(own.x + own.y + own.z)) return;
    sample[p] = own;
    replicate[p] = replicate_estimate(sums[p], spreads[p], first, samples[p]);
    for (std::size_t c = 0; c < 3; ++c) {
      if (own[c] == 0.0) replicate[p][c] = 0.0;  // equal samples, to the sums' resolution
    }
    classes[p] = count_class(samples[p]);
  });
  // Which count classes the image holds (a class is a bit width, so at most 32), in one pass.
  std::array<bool, 32> present{};
  for (const int c : classes)
    if (c >= 0) present[std::size_t(c)] = true;
  const auto classes_present = std::size_t(std::count(present.begin(), present.end(), true));
  // Each channel on its own: the gain differs between them (on the blue diffuse sphere of
  // `materials` red and green converge faster than blue, whose multiple bounces keep more of
  // their weight; one ratio for all three, weighted by blue's larger variance, understated red's
  // and green's 2.5x there at 1024 spp).
  std::vector<Vec3d> ratios(sums.size(), Vec3d{1, 1, 1});
  const bool uniform_counts = classes_present <= 1;
  ClassWindows windows;
  for (std::size_t channel = 0; channel < 3; ++channel) {
    // Each pixel's ratio from the neighbours of its own count class where there are enough of
    // them, else from the neighbours of every count.
    const std::vector<WindowTotal>& all =
        windows.of(width, height, replicate, sample, channel, classes, -1);
    for_each_pixel(sums.size(), [&](std::size_t p) {
      ratios[p][channel] = ratio_of_window(all[p].replicate, all[p].sample, all[p].pixels);
    });
    if (uniform_counts) continue;  // trimmed below, the three channels at once
    for (int c = 0; c < int(present.size()); ++c) {
      if (!present[std::size_t(c)]) continue;
      const std::vector<WindowTotal>& own =
          windows.of(width, height, replicate, sample, channel, classes, c);
      for_each_pixel(sums.size(), [&](std::size_t p) {
        if (classes[p] == c && own[p].pixels >= kReplicateMinNeighbours) {
          ratios[p][channel] = ratio_of(own[p].replicate, own[p].sample);
        }
      });
    }
  }
  if (uniform_counts) trimmed_ratios(width, height, replicate, sample, classes, ratios);
  return ratios;
}

std::vector<Vec3d> honest_variances(int width, int height, const std::vector<PixelSum>& sums,
                                    const std::vector<PixelSpread>& spreads,
                                    const std::vector<std::uint32_t>& samples, std::uint64_t first,
                                    SamplerKind sampler) {
  return honest_variances(replicate_ratios(width, height, sums, spreads, samples, first, sampler),
                          sums, spreads, samples, first, sampler);
}

std::vector<Vec3d> honest_variances(const std::vector<Vec3d>& ratios,
                                    const std::vector<PixelSum>& sums,
                                    const std::vector<PixelSpread>& spreads,
                                    const std::vector<std::uint32_t>& samples, std::uint64_t first,
                                    SamplerKind sampler) {
  std::vector<Vec3d> variances(sums.size());
  for_each_pixel(sums.size(), [&](std::size_t p) {
    const Vec3d own = variance_of_mean(sums[p], spreads[p], samples[p]);
    if (samples[p] < 2 || sampler == SamplerKind::Independent) {
      variances[p] = own;  // exact for independent samples; below two: infinite, unknown
      return;
    }
    const Vec3d replicates = replicate_estimate(sums[p], spreads[p], first, samples[p]);
    for (std::size_t c = 0; c < 3; ++c) {
      // Equal samples (to the sums' resolution) have no spread, and their replicates' means
      // differ only by rounding.
      variances[p][c] = own[c] == 0.0 ? 0.0
                                      : own[c] * ratios[p][c] * (1.0 - kOwnReplicateWeight) +
                                            replicates[c] * kOwnReplicateWeight;
    }
  });
  return variances;
}

}  // namespace rtiow
