#include "app/measure/accuracy_command.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/measure/accuracy_options.h"
#include "core/measure/accuracy_study.h"

namespace rtiow {
namespace {

// Every option checked before the reference (minutes of rendering) is made. The sample
// counts' limits depend on each other, so every one broken is named in the one line.
void check_options(const AccuracyOptions& o) {
  if (o.width < 1) throw InvalidInput("--width must be >= 1");
  std::vector<std::string> spp_problems;
  if (o.max_spp < 64) {
    spp_problems.push_back("--max-spp must be >= 64 (the fits and the budget sweep start at " +
                           std::string("16-32), got ") + std::to_string(o.max_spp));
  }
  if (std::int64_t(o.reference_spp) < 4 * std::int64_t(std::max(o.max_spp, 64))) {
    spp_problems.push_back("--reference-spp must be at least 4x --max-spp (" +
                           std::to_string(4 * std::int64_t(std::max(o.max_spp, 64))) +
                           ", or its noise swamps the errors), got " +
                           std::to_string(o.reference_spp));
  }
  if (o.fixed_spp < 2) {
    spp_problems.push_back("--fixed-spp must be >= 2, got " + std::to_string(o.fixed_spp));
  }
  if (o.book_spp < 16) {
    spp_problems.push_back("--book-spp must be >= 16, got " + std::to_string(o.book_spp));
  }
  if (!spp_problems.empty()) {
    std::string text;
    for (const std::string& p : spp_problems) text += (text.empty() ? "" : "; ") + p;
    throw InvalidInput(text);
  }
  // The two directories: missing ones are made, but a path that is a file is refused.
  check_output_directory(o.out_dir, "--out");
  if (!o.cache_dir.empty()) check_output_directory(o.cache_dir, "--cache-dir");
  if (o.repeat < 1) throw InvalidInput("--repeat must be >= 1");
  if (o.depths.empty() || *std::min_element(o.depths.begin(), o.depths.end()) < 1) {
    throw InvalidInput("--depths must list depth limits >= 1");
  }
  for (const double e : o.target_errors) {
    if (!(e > 0) || !std::isfinite(e)) throw InvalidInput("--target-errors must be > 0");
  }
  for (const double e : o.image_errors) {
    if (!(e > 0) || !std::isfinite(e)) throw InvalidInput("--image-errors must be > 0");
  }
}

}  // namespace

int run_accuracy_command(const AccuracyOptions& o) {
  check_options(o);
  return run_accuracy(o);
}

}  // namespace rtiow
