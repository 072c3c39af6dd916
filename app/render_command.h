#pragma once
// `rtiow render`: options, validation before any work, the render, and the output file.

#include <CLI/CLI.hpp>

#include <functional>

namespace rtiow {

// Adds the subcommand to `app`; the returned function runs it after parsing and returns
// the process exit code.
std::function<int()> add_render_command(CLI::App& app);

}  // namespace rtiow
