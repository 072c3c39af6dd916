#pragma once
// `rtiow diff REFERENCE TEST...`: compares images and exits as OpenImageIO's idiff does: a
// verdict (0 pass, 1 warning, 2 failure), or why there is none (3 the images differ in size or
// kind, 4 anything else: a missing or unreadable file, a bad option, an output refused).
// Noise-aware when both carry variance channels, or given several renders.

#include <CLI/CLI.hpp>

#include <functional>

namespace rtiow {

constexpr int kDiffImagesDiffer = 3;     // idiff's "images aren't even the same size"
constexpr int kDiffCouldNotCompare = 4;  // idiff's "could not find or open input files, etc."

std::function<int()> add_diff_command(CLI::App& app);

}  // namespace rtiow
