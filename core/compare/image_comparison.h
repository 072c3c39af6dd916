#pragma once
// A comparison as `rtiow diff` and the Python module's rtiow.diff make it: the mode chosen from
// the images (several renders: seeds; one with variances on both sides: noise; otherwise
// plain), the figures of that mode, the pixels that hold no number, and the verdict.

#include <optional>
#include <string>
#include <vector>

#include "core/compare/image_diff.h"

namespace rtiow {

struct ComparisonSettings {
  std::string mode = "auto";  // auto, plain, noise or seeds
  PlainThresholds thresholds;
  double alpha = 0.01;  // noise-aware: the chance that noise alone fails
  int block = 16;       // noise-aware: the side of a block of pixels
};

struct ImageComparison {
  std::string mode;  // the one used: plain, noise or seeds
  DiffInput test;    // the test, or the tests' mean where several (what is judged and pictured)
  std::optional<PlainDiff> plain;  // the figures of the mode used
  std::optional<NoiseDiff> noise;
  NonFinite non_finite;  // left out of the figures, and a failure
  DiffVerdict verdict = DiffVerdict::Pass;
  std::string description;  // the figures in one line
  DiffInput reference;      // the reference as read by compare_image_files (else empty)
};

// Compares images already read; throws ImagesNotComparable for one of another size or kind,
// InvalidInput for a mode the images cannot take.
ImageComparison compare_images(const DiffInput& reference, const std::vector<DiffInput>& tests,
                               const ComparisonSettings& settings);

// Reads the reference and the tests (refused, before they are read, where their number at the
// reference's size would take more than half of this machine's memory) and compares them; an
// image not comparable is named.
ImageComparison compare_image_files(const std::string& reference,
                                    const std::vector<std::string>& tests,
                                    const ComparisonSettings& settings);

}  // namespace rtiow
