#pragma once
// Image-diff for the regression tests, in the spirit of OpenImageIO's idiff: an image fails
// when more than `fail_percent` of its pixels differ by more than `fail_threshold`, or any
// pixel by more than `hard_fail`. Images are compared as a user sees them: gamma 2, clamped
// to [0, 1], so a single firefly in linear space cannot dominate.

#include <OpenImageIO/imagebuf.h>

#include <string>

#include "core/film/film.h"

namespace rtiow::test {

struct Thresholds {
  float fail_threshold;  // idiff -fail: a pixel "differs" beyond this
  float fail_percent;    // idiff -failpercent: allowed share of differing pixels
  float hard_fail;       // idiff -hardfail: no pixel may differ beyond this
};

struct ImageDiff {
  double mean_error = 0, rms_error = 0, psnr = 0, max_error = 0;
  int worst_x = 0, worst_y = 0;
  double failing_percent = 0;
  bool passed = false;
  std::string summary() const;  // one line: every figure above
};

// Linear film -> display-space float image.
OIIO::ImageBuf to_display(const Film& film);
// Linear image file (EXR) -> display-space float image; throws if unreadable.
OIIO::ImageBuf read_display(const std::string& path);

ImageDiff compare(const OIIO::ImageBuf& actual, const OIIO::ImageBuf& expected,
                  const Thresholds& t);

// Writes actual, expected and |actual - expected| scaled to be visible, as PNGs named
// <stem>-actual.png, <stem>-expected.png, <stem>-diff.png; returns the diff's path.
std::string write_failure_images(const OIIO::ImageBuf& actual, const OIIO::ImageBuf& expected,
                                 const std::string& stem);

}  // namespace rtiow::test
