#include "core/compare/image_diff.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>

#include "core/io/image_channels.h"
#include "core/limits/error.h"

namespace rtiow {
void check_comparable(const DiffInput& a, const DiffInput& b) {
  if (a.width != b.width || a.height != b.height) {
    throw ImagesNotComparable("the images differ in size: " + std::to_string(a.width) + "x" +
                              std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                              std::to_string(b.height));
  }
  if (a.linear != b.linear) {
    throw ImagesNotComparable(
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
  const ImageChannels in = read_image_channels(path, "image " + quote_value(path), 3);
  const std::size_t channels = in.names.size();
  const std::size_t pixels = std::size_t(in.width) * std::size_t(in.height);
  int rgb[3], variance[3];
  bool has_variance = true;
  for (int c = 0; c < 3; ++c) {
    const int named = in.index(std::string(1, "RGB"[c]));
    rgb[c] = named >= 0 ? named : c;  // unnamed channels: the first three
    variance[c] = in.index(std::string("variance.") + "RGB"[c]);
    has_variance = has_variance && variance[c] >= 0;
  }
  DiffInput image;
  image.width = in.width, image.height = in.height;
  switch (in.types[std::size_t(rgb[0])]) {
    case PixelType::Float:
      image.linear = true;
      break;
    case PixelType::Half:
      image.linear = true, image.relative_rounding = 0x1p-11;
      break;
    case PixelType::UInt8:
      image.relative_rounding = 0.0, image.absolute_rounding = 0.5 / 255.0;
      break;
    case PixelType::UInt16:
    case PixelType::UInt32:  // rare; read as 16-bit precision at best by most formats
      image.relative_rounding = 0.0, image.absolute_rounding = 0.5 / 65535.0;
      break;
  }
  image.rgb.resize(pixels * 3);
  if (has_variance) image.variance.resize(pixels * 3);
  for (std::size_t p = 0; p < pixels; ++p) {
    for (std::size_t c = 0; c < 3; ++c) {
      image.rgb[3 * p + c] = in.values[p * channels + std::size_t(rgb[c])];
      if (has_variance)
        image.variance[3 * p + c] = in.values[p * channels + std::size_t(variance[c])];
    }
  }
  return image;
}

DiffInput diff_input(const Film& film) {
  DiffInput image;
  image.width = film.width(), image.height = film.height(), image.linear = true;
  image.rgb.reserve(film.pixels().size() * 3);
  for (const Color& c : film.pixels()) image.rgb.insert(image.rgb.end(), {c.x, c.y, c.z});
  return image;
}

DiffInput display_referred(const DiffInput& linear) {
  DiffInput display;
  display.width = linear.width, display.height = linear.height, display.linear = false;
  display.relative_rounding = 0.5 * linear.relative_rounding;  // sqrt halves relative errors
  display.absolute_rounding = linear.absolute_rounding;
  display.rgb.resize(linear.rgb.size());
  for (std::size_t i = 0; i < linear.rgb.size(); ++i) {
    const float v = linear.rgb[i];
    // NaN stays NaN (reported, not hidden); everything else is clamped as on a screen.
    display.rgb[i] = std::isnan(v) ? v : std::sqrt(std::clamp(v, 0.0f, 1.0f));
  }
  return display;
}

DiffInput mean_image(const std::vector<DiffInput>& images) {
  DiffInput mean = images.at(0);
  mean.variance.clear();
  for (std::size_t k = 1; k < images.size(); ++k) {
    check_comparable(mean, images[k]);
    for (std::size_t i = 0; i < mean.rgb.size(); ++i) mean.rgb[i] += images[k].rgb[i];
  }
  for (float& v : mean.rgb) v /= float(images.size());
  return mean;
}

NonFinite find_non_finite(const DiffInput& test, const DiffInput& reference) {
  check_comparable(test, reference);
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
  check_comparable(test, reference);
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
  if (d.fail_percent > t.fail_percent || d.max_error > t.hard_fail || counted == 0) {
    d.verdict = DiffVerdict::Fail;
  } else if (d.warn_percent > t.warn_percent) {
    d.verdict = DiffVerdict::Warn;
  }
  return d;
}

std::string describe(const PlainDiff& d, const PlainThresholds& t) {
  char line[512];
  std::snprintf(line, sizeof line,
                "plain: mean error %.6g, RMS %.6g, max %.6g at (%d, %d); %.4g%% of pixels over %g "
                "(fail over %g%%), %.4g%% over %g (warn over %g%%)",
                d.mean_error, d.rms_error, d.max_error, d.worst_x, d.worst_y, d.fail_percent,
                t.fail, t.fail_percent, d.warn_percent, t.warn, t.warn_percent);
  return line;
}

}  // namespace rtiow
