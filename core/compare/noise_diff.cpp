// The noise-aware comparisons of core/compare/image_diff.h: against the images' own variance
// estimates (one test image), or against the spread of several renders with other seeds.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <utility>
#include <vector>

#include "core/compare/image_diff.h"
#include "core/compare/student_t.h"
#include "core/limits/error.h"
#include "core/limits/setting_name.h"

namespace rtiow {
namespace {

// The largest error the two images' storage can add to pixel p's difference, summed over its
// channels (half a step of each; see DiffInput).
double rounding_bound(const DiffInput& test, const DiffInput& reference, std::size_t p) {
  double bound = 0;
  for (std::size_t c = 0; c < 3; ++c) {
    const double value = std::abs(double(reference.rgb[3 * p + c]));
    bound += value * (test.relative_rounding + reference.relative_rounding) +
             test.absolute_rounding + reference.absolute_rounding;
  }
  return bound;
}

// A shared rounding error of up to `bound` (all of a block's pixels may round alike) as a
// variance: that of a uniform error on [-bound, bound]. Blocks round independently: the
// image-wide mean adds up their variances.
double rounding_variance(double bound) {
  return bound * bound / 3.0;
}

// The pixels of a block, row major, clipped to the image.
template <typename Visit>
void for_each_block_pixel(int width, int height, int block_size, int i, int j, Visit visit) {
  for (int y = j * block_size; y < std::min(height, (j + 1) * block_size); ++y) {
    for (int x = i * block_size; x < std::min(width, (i + 1) * block_size); ++x) {
      visit(std::size_t(y) * std::size_t(width) + std::size_t(x));
    }
  }
}

void record_block(NoiseDiff& d, int i, int j, int per_row, double z) {
  d.block_z[std::size_t(j * per_row + i)] = float(z);
  if (std::abs(z) > d.block_critical_z) ++d.failing_blocks;
  if (std::abs(z) > std::abs(d.worst_block_z)) {
    d.worst_block_z = z;
    d.worst_block_x = i * d.block_size, d.worst_block_y = j * d.block_size;
  }
}

}  // namespace

double normal_critical_value(double p) {
  // P(|Z| > z) = erfc(z / sqrt 2) falls from 1 at z = 0: bisect.
  double lo = 0.0, hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::sqrt(2.0)) > p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The levels the comparison's alpha is split into: half for the image-wide mean, half over
// the blocks (Bonferroni), so that noise alone fails the whole comparison with probability at
// most alpha. (Testing the mean and every block at alpha each failed about 2 alpha of unbiased
// seed pairs.)
double image_level(double alpha) {
  return alpha / 2.0;
}
double block_level(const NoiseDiff& d) {
  return d.alpha / 2.0 / double(d.blocks);
}

// The blocks of an image, each to be given a z (or t) score.
NoiseDiff start_blocks(int width, int height, int block_size, double alpha) {
  NoiseDiff d;
  d.block_size = block_size;
  d.alpha = alpha;
  d.blocks = ((width + block_size - 1) / block_size) * ((height + block_size - 1) / block_size);
  d.block_z.assign(std::size_t(d.blocks), 0.0f);
  return d;
}

void finish(NoiseDiff& d, double image_sum, double image_noise, double image_count) {
  if (image_count > 0) {
    d.mean_difference = image_sum / image_count;
    d.mean_difference_error = std::sqrt(image_noise) / image_count;
    d.image_z = image_sum / std::sqrt(std::max(image_noise, 1e-30));
  }
  const bool image_fails = std::abs(d.image_z) > d.image_critical_z;
  d.verdict = d.failing_blocks > 0 || image_fails ? DiffVerdict::Fail : DiffVerdict::Pass;
}

NoiseDiff noise_diff(const DiffInput& test, const DiffInput& reference, int block_size,
                     double alpha) {
  check_comparable(test, reference);
  if (test.variance.empty() || reference.variance.empty()) {
    throw InvalidInput(
        "the noise-aware comparison needs both images' variance channels (render with " +
        setting("stats_channels") + " to an .exr)");
  }
  NoiseDiff d = start_blocks(test.width, test.height, block_size, alpha);
  d.block_critical_z = normal_critical_value(block_level(d));
  d.image_critical_z = normal_critical_value(image_level(alpha));
  const int per_row = (test.width + block_size - 1) / block_size;
  const int rows = (test.height + block_size - 1) / block_size;
  double image_sum = 0, image_noise = 0, image_count = 0, image_rounding = 0;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < per_row; ++i) {
      double sum = 0, variance = 0, squares = 0, count = 0, rounding = 0;
      for_each_block_pixel(test.width, test.height, block_size, i, j, [&](std::size_t p) {
        if (!finite_pixel(test, p) || !finite_pixel(reference, p)) return;
        // Per pixel, over its three channels: one path gives all three, so they are
        // correlated; the variance of their sum is at most (sum of their deviations)^2.
        double difference = 0, deviation = 0;
        for (std::size_t c = 0; c < 3; ++c) {
          difference += double(test.rgb[3 * p + c]) - double(reference.rgb[3 * p + c]);
          deviation +=
              std::sqrt(double(test.variance[3 * p + c]) + double(reference.variance[3 * p + c]));
        }
        // A pixel with fewer than two samples has no noise estimate (infinite): left out.
        if (!std::isfinite(deviation)) return;
        sum += difference;
        squares += difference * difference;
        variance += deviation * deviation;
        rounding += rounding_bound(test, reference, p);
        count += 3;
      });
      // The noise of the block's mean difference: the images' own estimate, or the squared
      // differences themselves where they are larger. Per-pixel variances from a few dozen
      // samples run low where a pixel missed its rare bright paths; the differences of two
      // renders of one scene are symmetric about zero, and for symmetric terms
      // sum / sqrt(sum of squares) has Gaussian tails whatever their distribution (Efron
      // 1969). A bias adds only its square to the sum of squares. A block without noise
      // (all sky at 1 spp) is judged against a tiny floor, so any real difference shows.
      const double noise = std::max({variance, squares, 1e-30});
      image_sum += sum, image_noise += noise, image_count += count;
      const double error = noise + rounding_variance(rounding);
      image_rounding += rounding_variance(rounding);
      record_block(d, i, j, per_row, count > 0 ? sum / std::sqrt(error) : 0.0);
    }
  }
  finish(d, image_sum, image_noise + image_rounding, image_count);
  return d;
}

namespace {

// The spread of k renders' sums: their mean, and the variance of that mean.
std::pair<double, double> mean_and_variance(const std::vector<double>& sums) {
  const auto k = double(sums.size());
  double mean = 0, squares = 0;
  for (double s : sums) mean += s / k;
  for (double s : sums) squares += (s - mean) * (s - mean);
  return {mean, squares / (k - 1) / k};
}

// Block (i, j) of several renders against the reference: each render's sum of differences
// (into `sums`), the reference's variance, the rounding bound and the channels counted.
struct SeedsBlock {
  double reference_variance = 0, rounding = 0, count = 0;
};

SeedsBlock sum_seeds_block(const std::vector<DiffInput>& tests, const DiffInput& reference,
                           int block_size, int i, int j, std::vector<double>& sums) {
  std::fill(sums.begin(), sums.end(), 0.0);
  SeedsBlock b;
  const bool reference_has_variance = !reference.variance.empty();
  for_each_block_pixel(reference.width, reference.height, block_size, i, j, [&](std::size_t p) {
    // A pixel counts in every render or in none, so the k sums are alike.
    if (!finite_pixel(reference, p)) return;
    for (const DiffInput& test : tests) {
      if (!finite_pixel(test, p)) return;
    }
    double deviation = 0;  // the reference's, summed over its correlated channels
    if (reference_has_variance) {
      for (std::size_t c = 0; c < 3; ++c) {
        deviation += std::sqrt(double(reference.variance[3 * p + c]));
      }
    }
    if (!std::isfinite(deviation)) return;  // a reference pixel of fewer than 2 samples
    for (std::size_t r = 0; r < tests.size(); ++r) {
      for (std::size_t c = 0; c < 3; ++c) {
        sums[r] += double(tests[r].rgb[3 * p + c]) - double(reference.rgb[3 * p + c]);
      }
    }
    b.reference_variance += deviation * deviation;
    b.rounding += rounding_bound(tests[0], reference, p);
    b.count += 3;
  });
  return b;
}

}  // namespace

NoiseDiff seeds_diff(const std::vector<DiffInput>& tests, const DiffInput& reference,
                     int block_size, double alpha) {
  if (tests.size() < 2) {
    throw InvalidInput("comparing renders with other seeds needs at least two test images");
  }
  for (const DiffInput& test : tests) check_comparable(test, reference);
  const std::size_t k = tests.size();
  const double dof = double(k - 1);
  NoiseDiff d = start_blocks(reference.width, reference.height, block_size, alpha);
  d.renders = int(k);
  d.block_critical_z = student_t_critical_value(block_level(d), dof);
  d.image_critical_z = student_t_critical_value(image_level(alpha), dof);
  const int per_row = (reference.width + block_size - 1) / block_size;
  const int rows = (reference.height + block_size - 1) / block_size;
  std::vector<double> image_sums(k, 0.0), sums(k);
  double image_reference_variance = 0, image_count = 0, image_rounding = 0;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < per_row; ++i) {
      const SeedsBlock b = sum_seeds_block(tests, reference, block_size, i, j, sums);
      const auto [mean, variance] = mean_and_variance(sums);
      // Welch's statistic: the renders' mean against the reference, each with its own noise;
      // the t distribution of the renders' k - 1 degrees of freedom is the conservative one.
      const double noise =
          std::max(variance + b.reference_variance + rounding_variance(b.rounding), 1e-30);
      for (std::size_t r = 0; r < k; ++r) image_sums[r] += sums[r];
      image_reference_variance += b.reference_variance, image_count += b.count;
      image_rounding += rounding_variance(b.rounding);
      record_block(d, i, j, per_row, b.count > 0 ? mean / std::sqrt(noise) : 0.0);
    }
  }
  const auto [image_mean, image_variance] = mean_and_variance(image_sums);
  finish(d, image_mean, image_variance + image_reference_variance + image_rounding, image_count);
  return d;
}

std::string describe(const NoiseDiff& d) {
  char line[512];
  const char* statistic = d.renders > 1 ? "t" : "z";
  char source[96];
  if (d.renders > 1) {
    std::snprintf(source, sizeof source, "%d renders (t, %d d.o.f.)", d.renders, d.renders - 1);
  } else {
    std::snprintf(source, sizeof source, "variance channels (z)");
  }
  std::snprintf(line, sizeof line,
                "noise-aware, from %s: mean difference %.6g +- %.3g (%s = %.2f, critical %.2f); "
                "%d of %d blocks of %dx%d beyond |%s| = %.2f (alpha %g for the whole comparison, "
                "Bonferroni), worst %s = %.2f at (%d, %d)",
                source, d.mean_difference, d.mean_difference_error, statistic, d.image_z,
                d.image_critical_z, d.failing_blocks, d.blocks, d.block_size, d.block_size,
                statistic, d.block_critical_z, d.alpha, statistic, d.worst_block_z, d.worst_block_x,
                d.worst_block_y);
  return line;
}

}  // namespace rtiow
