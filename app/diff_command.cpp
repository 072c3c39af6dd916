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

}  // namespace

int run_diff_command(const DiffOptions& o) {
  // Exit codes 1 and 2 are verdicts: whatever keeps diff from giving one exits 3 or 4 (a
  // refusal before the outputs are claimed too).
  try {
    return run_diff(o);
  } catch (const CommandError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw CommandError("out of memory; nothing was compared", kDiffCouldNotCompare);
  } catch (const std::exception& e) {
    throw CommandError(e.what(), kDiffCouldNotCompare);
  }
}

}  // namespace rtiow
