#include "tests/image_compare.h"

#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace rtiow::test {
namespace {

OIIO::ImageBuf display_space(const OIIO::ImageBuf& linear) {
  OIIO::ImageBuf clamped = OIIO::ImageBufAlgo::clamp(linear, 0.0f, 1.0f);
  return OIIO::ImageBufAlgo::pow(clamped, 0.5f);
}

}  // namespace

std::string ImageDiff::summary() const {
  char line[256];
  std::snprintf(line, sizeof line,
                "mean %.5f, RMS %.5f, PSNR %.2f dB, worst %.4f at (%d, %d), %.3f%% of pixels "
                "over the threshold",
                mean_error, rms_error, psnr, max_error, worst_x, worst_y, failing_percent);
  return line;
}

OIIO::ImageBuf to_display(const Film& film) {
  OIIO::ImageBuf linear(OIIO::ImageSpec(film.width(), film.height(), 3, OIIO::TypeDesc::FLOAT));
  linear.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, film.pixels().data());
  return display_space(linear);
}

OIIO::ImageBuf read_display(const std::string& path) {
  OIIO::ImageBuf file(path);
  if (!file.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
    throw std::runtime_error("cannot read '" + path + "': " + file.geterror());
  }
  return display_space(file);
}

ImageDiff compare(const OIIO::ImageBuf& actual, const OIIO::ImageBuf& expected,
                  const Thresholds& t) {
  const auto r = OIIO::ImageBufAlgo::compare(actual, expected, t.fail_threshold, t.fail_threshold);
  ImageDiff d;
  d.mean_error = r.meanerror;
  d.rms_error = r.rms_error;
  d.psnr = r.PSNR;
  d.max_error = r.maxerror;
  d.worst_x = r.maxx;
  d.worst_y = r.maxy;
  const double pixels = double(actual.spec().width) * double(actual.spec().height);
  d.failing_percent = 100.0 * double(r.nfail) / pixels;
  // (r.error only says that some pixel failed: the fraction decides.)
  d.passed = d.failing_percent <= t.fail_percent && d.max_error <= t.hard_fail;
  return d;
}

std::string write_failure_images(const OIIO::ImageBuf& actual, const OIIO::ImageBuf& expected,
                                 const std::string& stem) {
  actual.write(stem + "-actual.png");
  expected.write(stem + "-expected.png");
  OIIO::ImageBuf diff = OIIO::ImageBufAlgo::absdiff(actual, expected);
  // Scale so the largest difference is white.
  const auto stats = OIIO::ImageBufAlgo::computePixelStats(diff);
  const float largest = std::max({stats.max[0], stats.max[1], stats.max[2], 1e-6f});
  diff = OIIO::ImageBufAlgo::mul(diff, 1.0f / largest);
  const std::string path = stem + "-diff.png";
  diff.write(path);
  return path;
}

}  // namespace rtiow::test
