#pragma once
// Comparing a test image with a reference, two ways (what `rtiow diff` runs):
//  - plain, in the spirit of OpenImageIO's idiff: a pixel "fails" when a channel differs by
//    more than a threshold; the image fails when more than a share of pixels do, or any
//    pixel differs by more than a hard limit. Fixed thresholds cannot tell noise from bias:
//    loose enough to pass a noisy render, they also pass a small bias.
//  - noise-aware, when both images carry the variance of each pixel's mean (rtiow's
//    --stats-channels EXR): the mean difference of each block of pixels is divided by its
//    standard error (a z-score; see noise_diff for the estimate), and the image fails when any
//    block's |z| exceeds the two-sided critical value at level alpha / (2 blocks) (Bonferroni), or
//    when the image-wide mean difference does at level alpha / 2. Noise alone fails with
//    probability <= alpha.
//  - several seeds: k >= 2 renders of the same job with different seeds, against one
//    reference. The renders' spread measures the noise, so no model of it is needed: each
//    block's mean over the k renders gets a Student t with k - 1 degrees of freedom (the
//    reference's own variance added where it has variance channels), alpha split the same way.
//
// Values are compared as stored: linear for float files, display-referred for 8-bit ones.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/film/film.h"
#include "core/limits/error.h"

namespace rtiow {

// An image as compared: R, G, B per pixel, and optionally the variance of each pixel's mean
// per channel (empty when the file has none).
struct DiffInput {
  int width = 0, height = 0;
  bool linear = false;          // float file (linear) or 8-bit (display-referred)
  std::vector<float> rgb;       // width * height * 3
  std::vector<float> variance;  // width * height * 3, or empty
  // Half a step of the storage at value v: |v| * relative_rounding + absolute_rounding
  // (float: 2^-24 relative, half: 2^-11, 8-bit: 1/510 absolute, 16-bit: 1/131070). Neighbours
  // of one colour round alike, so the noise-aware comparisons count it as a shared error of
  // each block, not as noise that averages out.
  double relative_rounding = 0x1p-24, absolute_rounding = 0.0;
};

// Reads R, G, B and, where present, variance.R/G/B. Throws InvalidInput naming the file
// when it cannot be read or has fewer than three channels.
DiffInput read_diff_input(const std::string& path);

// Throws InvalidInput when the two cannot be compared: other sizes, or a linear float image
// against an 8-bit display-referred one.
// Two images that cannot be compared as they are: of different sizes, or one linear float and
// the other 8-bit display-referred.
class ImagesNotComparable : public InvalidInput {
 public:
  using InvalidInput::InvalidInput;
};

void check_comparable(const DiffInput& a, const DiffInput& b);

// True when all three channels of pixel p are finite.
bool finite_pixel(const DiffInput& image, std::size_t p);

// A rendered film as a linear image without variances.
DiffInput diff_input(const Film& film);

// What a user sees: clamped to [0, 1] and encoded with the book's gamma 2 (variances dropped).
DiffInput display_referred(const DiffInput& linear);

enum class DiffVerdict { Pass = 0, Warn = 1, Fail = 2 };

std::string to_string(DiffVerdict verdict);

struct PlainThresholds {
  double fail = 1e-6;         // a channel differing by more fails its pixel
  double fail_percent = 0.0;  // the share of failing pixels allowed
  double hard_fail = 1e300;   // no channel may differ by more
  double warn = 1e-6;
  double warn_percent = 0.0;
};

struct PlainDiff {
  double mean_error = 0, rms_error = 0, max_error = 0;
  int worst_x = 0, worst_y = 0;
  double fail_percent = 0, warn_percent = 0;
  DiffVerdict verdict = DiffVerdict::Pass;
};

struct NoiseDiff {
  int renders = 1;  // test images; from 2 on, the statistic is Student's t (k - 1 d.o.f.)
  int block_size = 0, blocks = 0, failing_blocks = 0;
  double alpha = 0, block_critical_z = 0, worst_block_z = 0;
  int worst_block_x = 0, worst_block_y = 0;  // its top-left pixel
  double mean_difference = 0;                // test - reference, over pixels and channels
  double mean_difference_error = 0;          // its standard error
  double image_z = 0, image_critical_z = 0;
  std::vector<float> block_z;  // per block, row major ((width + b - 1) / b per row)
  DiffVerdict verdict = DiffVerdict::Pass;
};

// Pixels where either image has a NaN or an infinity (any channel): they are left out of
// every figure and reported, and make the comparison fail.
struct NonFinite {
  std::uint64_t pixels = 0;
  int first_x = -1, first_y = -1;
};

NonFinite find_non_finite(const DiffInput& test, const DiffInput& reference);

// All throw InvalidInput when the sizes differ (noise: when either lacks variances; seeds:
// with fewer than two tests).
PlainDiff plain_diff(const DiffInput& test, const DiffInput& reference, const PlainThresholds& t);
NoiseDiff noise_diff(const DiffInput& test, const DiffInput& reference, int block_size,
                     double alpha);
NoiseDiff seeds_diff(const std::vector<DiffInput>& tests, const DiffInput& reference,
                     int block_size, double alpha);

// One line each: every figure of the comparison, for a terminal or a test's failure message.
std::string describe(const PlainDiff& d, const PlainThresholds& t);
std::string describe(const NoiseDiff& d);

// The per-pixel mean of several images of one size (variances dropped).
DiffInput mean_image(const std::vector<DiffInput>& images);

// The two-sided standard normal critical value: P(|Z| > z) = p.
double normal_critical_value(double p);

}  // namespace rtiow
