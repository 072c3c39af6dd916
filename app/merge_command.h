#pragma once
// `rtiow merge PART... -o OUT`: adds shares of one render (from --sample-range or --part)
// into the image a single render would have produced.

#include <CLI/CLI.hpp>

#include <functional>

namespace rtiow {

std::function<int()> add_merge_command(CLI::App& app);

}  // namespace rtiow
