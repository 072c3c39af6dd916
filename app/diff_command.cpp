#include "app/diff_command.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "app/cli_checks.h"
#include "app/command_error.h"
#include "core/compare/diff_images.h"
#include "core/compare/diff_summary.h"
#include "core/compare/image_comparison.h"
#include "core/compare/image_diff.h"
#include "core/io/atomic_file.h"
#include "core/io/image_output.h"
#include "core/io/input_file.h"
#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/limits/image_size.h"

namespace rtiow {
namespace {

struct DiffOptions {
  std::string reference;
  std::vector<std::string> tests;
  ComparisonSettings settings;
  std::string out_diff, out_z;
  std::string summary_json;  // empty: none
};

// The comparison, its lines on stdout, its pictures and its summary; the verdict.
int compare_images(const DiffOptions& o) {
  const ImageComparison c = compare_image_files(o.reference, o.tests, o.settings);
  if (!o.out_z.empty() && c.mode == "plain") {
    throw InvalidInput(
        "--out-z needs a noise-aware comparison (both images with variances, or several "
        "renders)");
  }
  std::printf("%s\n", c.description.c_str());
  // Most pixels off by a little is what two renders of one job with other seeds look like:
  // a plain comparison cannot tell that noise from a change, and says which can.
  if (c.plain && o.settings.mode == "auto" && c.plain->verdict == DiffVerdict::Fail &&
      c.plain->fail_percent > 10.0) {
    std::printf(
        "note: %.0f%% of pixels differ: if these are renders of one job with other seeds, that "
        "is their noise; compare noise-aware: render both to .exr with --stats-channels, or "
        "give several renders of the job (rtiow diff reference.png s1.png s2.png s3.png); see "
        "rtiow diff --help\n",
        c.plain->fail_percent);
  }
  if (c.noise && !o.out_z.empty()) {
    write_image(o.out_z, z_image(*c.noise, c.test.width, c.test.height));
  }
  const NonFinite& bad = c.non_finite;
  if (bad.pixels > 0) {
    std::printf(
        "%llu pixels hold NaN or infinity (the first at (%d, %d)): left out, and a failure\n",
        static_cast<unsigned long long>(bad.pixels), bad.first_x, bad.first_y);
  }
  if (!o.out_diff.empty()) {
    write_image(o.out_diff, difference_image(c.test, c.reference));
  }
  std::printf("%s\n", to_string(c.verdict).c_str());
  if (!o.summary_json.empty()) {
    DiffSummary summary;
    summary.reference = o.reference, summary.tests = o.tests, summary.mode = c.mode;
    summary.width = c.test.width, summary.height = c.test.height;
    summary.plain = c.plain ? &*c.plain : nullptr, summary.noise = c.noise ? &*c.noise : nullptr;
    summary.thresholds = c.plain ? &o.settings.thresholds : nullptr;
    summary.non_finite = bad, summary.verdict = c.verdict;
    write_text_atomically(o.summary_json, diff_summary_json(summary));
  }
  return int(c.verdict);
}

// Exit codes 1 and 2 are verdicts: whatever keeps diff from giving one exits 3 or 4, and its
// summary (a script reads one for every exit) says so.
int run_diff(const DiffOptions& o) {
  std::vector<std::string> inputs{o.reference};
  inputs.insert(inputs.end(), o.tests.begin(), o.tests.end());
  if (!o.out_diff.empty()) check_image_output(o.out_diff, inputs);
  if (!o.out_z.empty()) check_image_output(o.out_z, inputs);
  if (!o.summary_json.empty()) check_output_path(o.summary_json, inputs, "--summary-json");
  // The outputs, claimed before the images are read.
  std::vector<std::unique_ptr<OutputClaim>> claims;
  for (const std::string* out : {&o.out_diff, &o.out_z, &o.summary_json}) {
    if (!out->empty()) claims.push_back(std::make_unique<OutputClaim>(*out));
  }
  const auto not_compared = [&](const std::string& why, int code) {
    if (!o.summary_json.empty()) {
      DiffSummary summary;
      summary.reference = o.reference, summary.tests = o.tests, summary.mode = o.settings.mode;
      summary.error = why, summary.exit_code = code;
      write_text_atomically(o.summary_json, diff_summary_json(summary));
    }
    return CommandError(why, code);
  };
  try {
    return compare_images(o);
  } catch (const ImagesNotComparable& e) {
    throw not_compared(e.what(), kDiffImagesDiffer);
  } catch (const std::bad_alloc&) {
    throw not_compared("out of memory; nothing was compared", kDiffCouldNotCompare);
  } catch (const std::exception& e) {
    throw not_compared(e.what(), kDiffCouldNotCompare);
  }
}

// A plain comparison's thresholds.
void add_plain_options(CLI::App* cmd, PlainThresholds& t) {
  cmd->add_option("--fail", t.fail, "Plain: a pixel fails when a channel differs by more")
      ->check(kFiniteNotNegative)
      ->capture_default_str();
  cmd->add_option("--failpercent", t.fail_percent,
                  "Plain: the percentage of failing pixels allowed")
      ->check(kFiniteNotNegative)
      ->capture_default_str();
  cmd->add_option("--hardfail", t.hard_fail,
                  "Plain: fail when any channel differs by more (default: no limit)")
      ->check(kFiniteNotNegative);
  cmd->add_option("--warn", t.warn,
                  "Plain: a pixel warns when a channel differs by more (default: --fail's value "
                  "when --fail is given)")
      ->check(kFiniteNotNegative)
      ->capture_default_str();
  cmd->add_option("--warnpercent", t.warn_percent,
                  "Plain: the percentage of warning pixels allowed (default: --failpercent's "
                  "value when --failpercent is given)")
      ->check(kFiniteNotNegative)
      ->capture_default_str();
}

// A noise-aware comparison's test.
void add_noise_options(CLI::App* cmd, ComparisonSettings& s) {
  cmd->add_option("--alpha", s.alpha,
                  "Noise-aware: the chance that noise alone fails the comparison (half for the "
                  "image mean, half over the blocks), 1e-12 to 0.5")
      ->check(kFiniteNotNegative)
      ->check(from_to(1e-12, 0.5))
      ->capture_default_str();
  cmd->add_option("--block", s.block, "Noise-aware: the side of a block of pixels, 1 to 4096")
      ->check(from_to(1, 4096))
      ->capture_default_str();
}

}  // namespace

std::function<int()> add_diff_command(CLI::App& app) {
  auto o = std::make_shared<DiffOptions>();
  CLI::App* cmd = app.add_subcommand(
      "diff",
      "Compare a test image, or several renders with other seeds, with a reference. Exit 0 "
      "pass, 1 warning, 2 failure; no verdict: 3 images of other sizes (or linear against "
      "8-bit), 4 a missing or unreadable file or a bad option. Noise-aware when given several "
      "renders or when both images carry variance channels (--stats-channels EXR): then a "
      "difference fails only where the noise cannot explain it");
  cmd->add_option("reference", o->reference, "The reference image")->required();
  cmd->add_option("test", o->tests,
                  "The image to check, or several renders of the same job with other seeds")
      ->required();
  cmd->add_option("--mode", o->settings.mode,
                  "auto (seeds for several tests; noise when both images have variances; else "
                  "plain), plain, noise, or seeds")
      ->check(CLI::IsMember({"auto", "plain", "noise", "seeds"}))
      ->capture_default_str();
  add_plain_options(cmd, o->settings.thresholds);
  add_noise_options(cmd, o->settings);
  cmd->add_option("--out-diff", o->out_diff,
                  "Write |test - reference| (several tests: their mean), scaled so the largest "
                  "difference is white");
  cmd->add_option("--summary-json", o->summary_json,
                  "Also write the verdict and the figures as JSON here, for scripts (schema in "
                  "docs/diff.md)");
  cmd->add_option("--out-z", o->out_z,
                  "Noise-aware: write the blocks' z (or t) scores (red: test brighter, blue: "
                  "darker, full colour at the critical value)");
  return [o, cmd] {
    if (!cmd->parsed()) return -1;
    // A warning threshold left unset follows the failure one given, so plain thresholds for
    // failure alone do not leave every image warning at 1e-6.
    if (cmd->count("--fail") > 0 && cmd->count("--warn") == 0) {
      o->settings.thresholds.warn = o->settings.thresholds.fail;
    }
    if (cmd->count("--failpercent") > 0 && cmd->count("--warnpercent") == 0) {
      o->settings.thresholds.warn_percent = o->settings.thresholds.fail_percent;
    }
    // Exit codes 1 and 2 are verdicts: whatever keeps diff from giving one exits 3 or 4 (a
    // refusal before the outputs are claimed too).
    try {
      return run_diff(*o);
    } catch (const CommandError&) {
      throw;
    } catch (const std::bad_alloc&) {
      throw CommandError("out of memory; nothing was compared", kDiffCouldNotCompare);
    } catch (const std::exception& e) {
      throw CommandError(e.what(), kDiffCouldNotCompare);
    }
  };
}

}  // namespace rtiow
