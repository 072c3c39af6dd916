#include "app/diff_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "core/film/film.h"
#include "core/film/image_diff.h"
#include "core/io/error.h"
#include "core/io/image_output.h"
#include "core/io/output_path.h"

namespace rtiow {
namespace {

struct DiffOptions {
  std::string reference, test;
  std::string mode = "auto";
  PlainThresholds thresholds;
  double alpha = 0.01;
  int block = 16;
  std::string out_diff, out_z;
};

// |test - reference| per channel, scaled so the largest difference is 1.
Film difference_image(const DiffInput& test, const DiffInput& reference) {
  Film film(test.width, test.height);
  float largest = 1e-12f;
  for (std::size_t i = 0; i < test.rgb.size(); ++i) {
    const float e = std::abs(test.rgb[i] - reference.rgb[i]);
    if (std::isfinite(e)) largest = std::max(largest, e);
  }
  for (int y = 0; y < test.height; ++y) {
    for (int x = 0; x < test.width; ++x) {
      const std::size_t p = 3 * (std::size_t(y) * std::size_t(test.width) + std::size_t(x));
      const auto scaled = [&](std::size_t c) {
        const float e = std::abs(test.rgb[p + c] - reference.rgb[p + c]) / largest;
        return std::isfinite(e) ? e : 1.0f;  // NaN and infinities show as white
      };
      film.at(x, y) = {scaled(0), scaled(1), scaled(2)};
    }
  }
  return film;
}

// Each block coloured by its z-score: red where the test is brighter, blue where darker,
// full at the critical value; grey where nothing shows.
Film z_image(const NoiseDiff& d, int width, int height) {
  Film film(width, height);
  const int per_row = (width + d.block_size - 1) / d.block_size;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float z = d.block_z[std::size_t((y / d.block_size) * per_row + x / d.block_size)];
      const float level = std::min(1.0f, std::abs(z) / float(d.block_critical_z));
      const float grey = 0.1f * (1.0f - level);
      film.at(x, y) = z > 0 ? Color{grey + level, grey, grey} : Color{grey, grey, grey + level};
    }
  }
  return film;
}

void print_plain(const PlainDiff& d, const PlainThresholds& t) {
  std::printf(
      "plain: mean error %.6g, RMS %.6g, max %.6g at (%d, %d); %.4g%% of pixels over %g "
      "(fail over %g%%), %.4g%% over %g (warn over %g%%)\n",
      d.mean_error, d.rms_error, d.max_error, d.worst_x, d.worst_y, d.fail_percent, t.fail,
      t.fail_percent, d.warn_percent, t.warn, t.warn_percent);
}

void print_noise(const NoiseDiff& d) {
  std::printf(
      "noise-aware: mean difference %.6g +- %.3g (z = %.2f, critical %.2f); %d of %d blocks of "
      "%dx%d beyond |z| = %.2f (alpha %g, Bonferroni), worst z = %.2f at (%d, %d)\n",
      d.mean_difference, d.mean_difference_error, d.image_z, d.image_critical_z, d.failing_blocks,
      d.blocks, d.block_size, d.block_size, d.block_critical_z, d.alpha, d.worst_block_z,
      d.worst_block_x, d.worst_block_y);
}

int run_diff(const DiffOptions& o) {
  if (!o.out_diff.empty()) check_image_output(o.out_diff, {o.reference, o.test});
  if (!o.out_z.empty()) check_image_output(o.out_z, {o.reference, o.test});
  const DiffInput reference = read_diff_input(o.reference);
  const DiffInput test = read_diff_input(o.test);
  const bool noisy = !reference.variance.empty() && !test.variance.empty();
  if (o.mode == "noise" && !noisy) {
    throw InvalidInput(
        "--mode noise needs both images' variance channels (render with --stats-channels to "
        "an .exr)");
  }
  if (!o.out_z.empty() && !(noisy && o.mode != "plain")) {
    throw InvalidInput("--out-z needs the noise-aware comparison (both images with variances)");
  }
  const NonFinite bad = find_non_finite(test, reference);
  DiffVerdict verdict = DiffVerdict::Pass;
  if (o.mode == "plain" || !noisy) {
    const PlainDiff d = plain_diff(test, reference, o.thresholds);
    print_plain(d, o.thresholds);
    verdict = d.verdict;
  } else {
    const NoiseDiff d = noise_diff(test, reference, o.block, o.alpha);
    print_noise(d);
    verdict = d.verdict;
    if (!o.out_z.empty()) write_image(o.out_z, z_image(d, test.width, test.height));
  }
  if (bad.pixels > 0) {
    std::printf(
        "%llu pixels hold NaN or infinity (the first at (%d, %d)): left out, and a failure\n",
        static_cast<unsigned long long>(bad.pixels), bad.first_x, bad.first_y);
    verdict = DiffVerdict::Fail;
  }
  if (!o.out_diff.empty()) write_image(o.out_diff, difference_image(test, reference));
  std::printf("%s\n", to_string(verdict).c_str());
  return int(verdict);
}

}  // namespace

std::function<int()> add_diff_command(CLI::App& app) {
  auto o = std::make_shared<DiffOptions>();
  CLI::App* cmd = app.add_subcommand(
      "diff",
      "Compare a test image with a reference: exit 0 pass, 1 warning, 2 failure (or refused "
      "input). Noise-aware when both carry variance channels (--stats-channels EXR): then a "
      "difference fails only where the noise cannot explain it");
  cmd->add_option("reference", o->reference, "The reference image")->required();
  cmd->add_option("test", o->test, "The image to check")->required();
  cmd->add_option("--mode", o->mode,
                  "auto (noise-aware when both images have variances), plain, or noise")
      ->check(CLI::IsMember({"auto", "plain", "noise"}))
      ->capture_default_str();
  cmd->add_option("--fail", o->thresholds.fail,
                  "Plain: a pixel fails when a channel differs by more")
      ->capture_default_str();
  cmd->add_option("--failpercent", o->thresholds.fail_percent,
                  "Plain: the percentage of failing pixels allowed")
      ->capture_default_str();
  cmd->add_option("--hardfail", o->thresholds.hard_fail,
                  "Plain: fail when any channel differs by more (default: no limit)");
  cmd->add_option("--warn", o->thresholds.warn,
                  "Plain: a pixel warns when a channel differs by more")
      ->capture_default_str();
  cmd->add_option("--warnpercent", o->thresholds.warn_percent,
                  "Plain: the percentage of warning pixels allowed")
      ->capture_default_str();
  cmd->add_option("--alpha", o->alpha,
                  "Noise-aware: the chance that noise alone fails a block or the image mean")
      ->check(CLI::Range(1e-12, 0.5))
      ->capture_default_str();
  cmd->add_option("--block", o->block, "Noise-aware: the side of a block of pixels")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  cmd->add_option("--out-diff", o->out_diff,
                  "Write |test - reference|, scaled so the largest difference is white");
  cmd->add_option("--out-z", o->out_z,
                  "Noise-aware: write the blocks' z-scores (red: test brighter, blue: darker, "
                  "full colour at the critical value)");
  return [o, cmd] { return cmd->parsed() ? run_diff(*o) : -1; };
}

}  // namespace rtiow
