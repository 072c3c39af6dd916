#pragma once
// `rtiow diff REFERENCE TEST...`: compares images and exits as OpenImageIO's idiff does: a
// verdict (0 pass, 1 warning, 2 failure), or why there is none (3 the images differ in size or
// kind, 4 anything else: a missing or unreadable file, a bad option, an output refused).
// Noise-aware when both carry variance channels, or given several renders.

#include <string>
#include <vector>

#include "core/compare/image_comparison.h"

namespace rtiow {

constexpr int kDiffImagesDiffer = 3;     // idiff's "images aren't even the same size"
constexpr int kDiffCouldNotCompare = 4;  // idiff's "could not find or open input files, etc."

struct DiffOptions {
  std::string reference;
  std::vector<std::string> tests;
  ComparisonSettings settings;
  std::string out_diff, out_z;
  std::string summary_json;  // empty: none
};

// Compares and prints the verdict; its exit code. What keeps it from a verdict is a
// CommandError of exit code 3 or 4.
int run_diff_command(const DiffOptions& o);

}  // namespace rtiow
