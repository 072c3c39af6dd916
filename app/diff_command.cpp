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
#include "app/diff_summary.h"
#include "core/compare/diff_images.h"
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
  std::string mode = "auto";
  PlainThresholds thresholds;
  double alpha = 0.01;
  int block = 16;
  std::string out_diff, out_z;
  std::string summary_json;  // empty: none
};

// Refuses, before reading them, more images of the reference's size than half of this
// machine's memory holds (each read image keeps R, G, B and their variances as floats).
void check_memory_for(std::size_t images, const DiffInput& reference) {
  const std::uint64_t per_image =
      std::uint64_t(reference.width) * std::uint64_t(reference.height) * 6 * sizeof(float);
  const std::uint64_t available = physical_memory_bytes();
  if (per_image * images > available / 2) {
    throw InvalidInput(
        std::to_string(images) + " images of " + std::to_string(reference.width) + "x" +
        std::to_string(reference.height) + " need " + std::to_string((per_image * images) >> 20) +
        " MiB, more than half of this machine's " + std::to_string(available >> 20) + " MiB");
  }
}

// auto: several tests -> seeds; one, both with variances -> noise; otherwise plain.
std::string chosen_mode(const DiffOptions& o, const DiffInput& reference,
                        const std::vector<DiffInput>& tests) {
  const bool several = tests.size() > 1;
  const bool variances = !reference.variance.empty() && !tests[0].variance.empty();
  if (o.mode == "auto") return several ? "seeds" : variances ? "noise" : "plain";
  if (several && o.mode != "seeds") {
    throw InvalidInput("--mode " + o.mode +
                       " compares one test image; several are compared with --mode seeds");
  }
  if (o.mode == "seeds" && !several) {
    throw InvalidInput(
        "--mode seeds needs at least two test images (renders of the same job with other "
        "seeds)");
  }
  if (o.mode == "noise" && !variances) {
    throw InvalidInput(
        "--mode noise needs both images' variance channels (render with --stats-channels to "
        "an .exr)");
  }
  return o.mode;
}

int compare_images(const DiffOptions& o, const std::vector<std::string>& inputs) {
  const DiffInput reference = read_diff_input(o.reference);
  check_memory_for(inputs.size(), reference);
  std::vector<DiffInput> tests;
  for (const std::string& path : o.tests) {
    tests.push_back(read_diff_input(path));
    try {
      check_comparable(tests.back(), reference);
    } catch (const ImagesNotComparable& e) {
      throw ImagesNotComparable("image " + quote_value(path) +
                                " against the reference: " + e.what());
    }
  }
  const std::string mode = chosen_mode(o, reference, tests);
  if (!o.out_z.empty() && mode == "plain") {
    throw InvalidInput(
        "--out-z needs a noise-aware comparison (both images with variances, or several "
        "renders)");
  }
  // Several renders are judged, and pictured, by their mean.
  const DiffInput test = tests.size() > 1 ? mean_image(tests) : tests[0];
  const NonFinite bad = find_non_finite(test, reference);
  DiffVerdict verdict = DiffVerdict::Pass;
  DiffSummary summary;
  summary.reference = o.reference, summary.tests = o.tests, summary.mode = mode;
  summary.width = test.width, summary.height = test.height;
  std::optional<PlainDiff> plain;
  std::optional<NoiseDiff> noise;
  if (mode == "plain") {
    const PlainDiff& d = plain.emplace(plain_diff(test, reference, o.thresholds));
    summary.plain = &d, summary.thresholds = &o.thresholds;
    std::printf("%s\n", describe(d, o.thresholds).c_str());
    verdict = d.verdict;
    // Most pixels off by a little is what two renders of one job with other seeds look like:
    // a plain comparison cannot tell that noise from a change, and says which can.
    if (o.mode == "auto" && d.verdict == DiffVerdict::Fail && d.fail_percent > 10.0) {
      std::printf(
          "note: %.0f%% of pixels differ: if these are renders of one job with other seeds, that "
          "is their noise; compare noise-aware: render both to .exr with --stats-channels, or "
          "give several renders of the job (rtiow diff reference.png s1.png s2.png s3.png); see "
          "rtiow diff --help\n",
          d.fail_percent);
    }
  } else {
    const NoiseDiff& d =
        noise.emplace(mode == "seeds" ? seeds_diff(tests, reference, o.block, o.alpha)
                                      : noise_diff(test, reference, o.block, o.alpha));
    summary.noise = &d;
    std::printf("%s\n", describe(d).c_str());
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
  if (!o.summary_json.empty()) {
    summary.non_finite = bad, summary.verdict = verdict;
    write_text_atomically(o.summary_json, diff_summary_json(summary));
  }
  return int(verdict);
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
      summary.reference = o.reference, summary.tests = o.tests, summary.mode = o.mode;
      summary.error = why, summary.exit_code = code;
      write_text_atomically(o.summary_json, diff_summary_json(summary));
    }
    return CommandError(why, code);
  };
  try {
    return compare_images(o, inputs);
  } catch (const ImagesNotComparable& e) {
    throw not_compared(e.what(), kDiffImagesDiffer);
  } catch (const std::bad_alloc&) {
    throw not_compared("out of memory; nothing was compared", kDiffCouldNotCompare);
  } catch (const std::exception& e) {
    throw not_compared(e.what(), kDiffCouldNotCompare);
  }
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
  cmd->add_option("--mode", o->mode,
                  "auto (seeds for several tests; noise when both images have variances; else "
                  "plain), plain, noise, or seeds")
      ->check(CLI::IsMember({"auto", "plain", "noise", "seeds"}))
      ->capture_default_str();
  cmd->add_option("--fail", o->thresholds.fail,
                  "Plain: a pixel fails when a channel differs by more")
      ->check(kFiniteNotNegative)
      ->capture_default_str();
  cmd->add_option("--failpercent", o->thresholds.fail_percent,
                  "Plain: the percentage of failing pixels allowed")
      ->check(kFiniteNotNegative)
      ->capture_default_str();
  cmd->add_option("--hardfail", o->thresholds.hard_fail,
                  "Plain: fail when any channel differs by more (default: no limit)")
      ->check(kFiniteNotNegative);
  cmd->add_option("--warn", o->thresholds.warn,
                  "Plain: a pixel warns when a channel differs by more (default: --fail's value "
                  "when --fail is given)")
      ->check(kFiniteNotNegative)
      ->capture_default_str();
  cmd->add_option("--warnpercent", o->thresholds.warn_percent,
                  "Plain: the percentage of warning pixels allowed (default: --failpercent's "
                  "value when --failpercent is given)")
      ->check(kFiniteNotNegative)
      ->capture_default_str();
  cmd->add_option("--alpha", o->alpha,
                  "Noise-aware: the chance that noise alone fails the comparison (half for the "
                  "image mean, half over the blocks), 1e-12 to 0.5")
      ->check(kFiniteNotNegative)
      ->check(from_to(1e-12, 0.5))
      ->capture_default_str();
  cmd->add_option("--block", o->block, "Noise-aware: the side of a block of pixels, 1 to 4096")
      ->check(from_to(1, 4096))
      ->capture_default_str();
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
      o->thresholds.warn = o->thresholds.fail;
    }
    if (cmd->count("--failpercent") > 0 && cmd->count("--warnpercent") == 0) {
      o->thresholds.warn_percent = o->thresholds.fail_percent;
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
