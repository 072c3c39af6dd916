#include "core/film/image_diff.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/io/error.h"
#include "core/io/image_backend.h"
#include "core/io/image_file.h"
#include "core/io/input_file.h"
#include "core/io/input_limits.h"
#include "core/render/render.h"

namespace rtiow {
namespace {

int channel_index(const ImageHeader& header, const std::string& name) {
  const auto& names = header.channel_names;
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : int(it - names.begin());
}

void check_same_size(const DiffInput& a, const DiffInput& b) {
  if (a.width != b.width || a.height != b.height) {
    throw InvalidInput("the images differ in size: " + std::to_string(a.width) + "x" +
                       std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                       std::to_string(b.height));
  }
  if (a.linear != b.linear) {
    throw InvalidInput(
        "one image is linear float and the other 8-bit display-referred: compare like with "
        "like");
  }
}

bool finite_pixel(const DiffInput& image, std::size_t p) {
  for (std::size_t c = 0; c < 3; ++c) {
    if (!std::isfinite(image.rgb[3 * p + c])) return false;
  }
  return true;
}

}  // namespace

std::string to_string(DiffVerdict verdict) {
  switch (verdict) {
    case DiffVerdict::Pass:
      return "PASS";
    case DiffVerdict::Warn:
      return "WARNING";
    case DiffVerdict::Fail:
      break;
  }
  return "FAILURE";
}

DiffInput read_diff_input(const std::string& path) {
  check_input_file(path, limits::kMaxPartFileBytes, "image");
  const std::string name = "image " + quote_value(path);
  std::string reason;
  auto in = image_backend().open(path, reason);
  if (!in) throw InvalidInput(name + ": cannot read: " + one_line(reason, 200));
  const ImageHeader& header = in->header();
  const std::size_t channels = header.channel_names.size();
  if (header.width < 1 || header.height < 1 || header.width > limits::kMaxImageSide ||
      header.height > limits::kMaxImageSide || channels < 3 || channels > 64) {
    throw InvalidInput(name + ": " + std::to_string(header.width) + "x" +
                       std::to_string(header.height) + " with " + std::to_string(channels) +
                       " channels is not an image rtiow compares (R, G, B needed)");
  }
  RenderSettings size;  // the header decides what is allocated: the render's own limits
  size.width = header.width, size.height = header.height;
  try {
    validate(size);
  } catch (const InvalidInput& e) {
    throw InvalidInput(name + ": " + e.what());
  }
  const std::size_t pixels = std::size_t(header.width) * std::size_t(header.height);
  std::vector<float> values(pixels * channels);
  if (!in->read_pixels(PixelType::Float, values.data(), reason)) {
    throw InvalidInput(name + ": cannot read its pixels: " + one_line(reason, 200));
  }
  int rgb[3], variance[3];
  bool has_variance = true;
  for (int c = 0; c < 3; ++c) {
    const int named = channel_index(header, std::string(1, "RGB"[c]));
    rgb[c] = named >= 0 ? named : c;  // unnamed channels: the first three
    variance[c] = channel_index(header, std::string("variance.") + "RGB"[c]);
    has_variance = has_variance && variance[c] >= 0;
  }
  DiffInput image;
  image.width = header.width, image.height = header.height;
  image.linear = header.channel_types[std::size_t(rgb[0])] == PixelType::Float;
  image.rgb.resize(pixels * 3);
  if (has_variance) image.variance.resize(pixels * 3);
  for (std::size_t p = 0; p < pixels; ++p) {
    for (std::size_t c = 0; c < 3; ++c) {
      image.rgb[3 * p + c] = values[p * channels + std::size_t(rgb[c])];
      if (has_variance) image.variance[3 * p + c] = values[p * channels + std::size_t(variance[c])];
    }
  }
  return image;
}

NonFinite find_non_finite(const DiffInput& test, const DiffInput& reference) {
  check_same_size(test, reference);
  NonFinite found;
  const std::size_t pixels = std::size_t(test.width) * std::size_t(test.height);
  for (std::size_t p = 0; p < pixels; ++p) {
    if (finite_pixel(test, p) && finite_pixel(reference, p)) continue;
    if (found.pixels++ == 0) {
      found.first_x = int(p % std::size_t(test.width));
      found.first_y = int(p / std::size_t(test.width));
    }
  }
  return found;
}

PlainDiff plain_diff(const DiffInput& test, const DiffInput& reference, const PlainThresholds& t) {
  check_same_size(test, reference);
  PlainDiff d;
  const std::size_t pixels = std::size_t(test.width) * std::size_t(test.height);
  double sum = 0, sum_squares = 0;
  std::uint64_t failing = 0, warning = 0, counted = 0;
  for (std::size_t p = 0; p < pixels; ++p) {
    if (!finite_pixel(test, p) || !finite_pixel(reference, p)) continue;
    double worst = 0;
    for (std::size_t c = 0; c < 3; ++c) {
      const double e = std::abs(double(test.rgb[3 * p + c]) - double(reference.rgb[3 * p + c]));
      sum += e, sum_squares += e * e, ++counted;
      worst = std::max(worst, e);
    }
    if (worst > d.max_error) {
      d.max_error = worst;
      d.worst_x = int(p % std::size_t(test.width)), d.worst_y = int(p / std::size_t(test.width));
    }
    failing += worst > t.fail;
    warning += worst > t.warn;
  }
  const double n = double(std::max<std::uint64_t>(counted, 1));
  d.mean_error = sum / n;
  d.rms_error = std::sqrt(sum_squares / n);
  d.fail_percent = 100.0 * double(failing) / double(pixels);
  d.warn_percent = 100.0 * double(warning) / double(pixels);
  if (d.fail_percent > t.fail_percent || d.max_error > t.hard_fail) {
    d.verdict = DiffVerdict::Fail;
  } else if (d.warn_percent > t.warn_percent) {
    d.verdict = DiffVerdict::Warn;
  }
  return d;
}

double normal_critical_value(double p) {
  // P(|Z| > z) = erfc(z / sqrt 2) falls from 1 at z = 0: bisect.
  double lo = 0.0, hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::sqrt(2.0)) > p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

NoiseDiff noise_diff(const DiffInput& test, const DiffInput& reference, int block_size,
                     double alpha) {
  check_same_size(test, reference);
  if (test.variance.empty() || reference.variance.empty()) {
    throw InvalidInput(
        "the noise-aware comparison needs both images' variance channels (render with "
        "--stats-channels to an .exr)");
  }
  NoiseDiff d;
  d.block_size = block_size;
  d.alpha = alpha;
  const int bx = (test.width + block_size - 1) / block_size;
  const int by = (test.height + block_size - 1) / block_size;
  d.blocks = bx * by;
  d.block_critical_z = normal_critical_value(alpha / double(d.blocks));
  d.image_critical_z = normal_critical_value(alpha);
  d.block_z.assign(std::size_t(d.blocks), 0.0f);
  double image_sum = 0, image_variance = 0, image_count = 0;
  for (int j = 0; j < by; ++j) {
    for (int i = 0; i < bx; ++i) {
      double sum = 0, variance = 0, squares = 0, count = 0;
      for (int y = j * block_size; y < std::min(test.height, (j + 1) * block_size); ++y) {
        for (int x = i * block_size; x < std::min(test.width, (i + 1) * block_size); ++x) {
          const std::size_t p = std::size_t(y) * std::size_t(test.width) + std::size_t(x);
          if (!finite_pixel(test, p) || !finite_pixel(reference, p)) continue;
          // Per pixel, over its three channels: one path gives all three, so they are
          // correlated; the variance of their sum is at most (sum of their deviations)^2.
          double difference = 0, deviation = 0;
          for (std::size_t c = 0; c < 3; ++c) {
            difference += double(test.rgb[3 * p + c]) - double(reference.rgb[3 * p + c]);
            deviation +=
                std::sqrt(double(test.variance[3 * p + c]) + double(reference.variance[3 * p + c]));
          }
          // A pixel with fewer than two samples has no noise estimate (infinite): left out.
          if (!std::isfinite(deviation)) continue;
          sum += difference;
          squares += difference * difference;
          variance += deviation * deviation;
          count += 3;
        }
      }
      // The noise of the block's mean difference: the images' own estimate, or the squared
      // differences themselves where they are larger. Per-pixel variances from a few dozen
      // samples run low where a pixel missed its rare bright paths; the differences of two
      // renders of one scene are symmetric about zero, and for symmetric terms
      // sum / sqrt(sum of squares) has Gaussian tails whatever their distribution (Efron
      // 1969). A bias adds only its square to the sum of squares. A block without noise
      // (all sky at 1 spp) is judged against a tiny floor, so any real difference shows.
      const double noise = std::max({variance, squares, 1e-30});
      image_sum += sum, image_variance += noise, image_count += count;
      const double z = count > 0 ? sum / std::sqrt(noise) : 0.0;
      d.block_z[std::size_t(j * bx + i)] = float(z);
      if (std::abs(z) > d.block_critical_z) ++d.failing_blocks;
      if (std::abs(z) > std::abs(d.worst_block_z)) {
        d.worst_block_z = z;
        d.worst_block_x = i * block_size, d.worst_block_y = j * block_size;
      }
    }
  }
  if (image_count > 0) {
    d.mean_difference = image_sum / image_count;
    d.mean_difference_error = std::sqrt(image_variance) / image_count;
    d.image_z = image_sum / std::sqrt(std::max(image_variance, 1e-30));
  }
  const bool image_fails = std::abs(d.image_z) > d.image_critical_z;
  d.verdict = d.failing_blocks > 0 || image_fails ? DiffVerdict::Fail : DiffVerdict::Pass;
  return d;
}

}  // namespace rtiow
