#pragma once
// `rtiow diff REFERENCE TEST`: compares two images and exits as idiff does (0 pass,
// 1 warning, 2 failure or refused input). Noise-aware when both carry variance channels.

#include <CLI/CLI.hpp>

#include <functional>

namespace rtiow {

std::function<int()> add_diff_command(CLI::App& app);

}  // namespace rtiow
