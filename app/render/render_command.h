#pragma once
// `rtiow render`: options, validation before any work, the render, and the output file.

#include <CLI/CLI.hpp>

#include <functional>

namespace rtiow {

// Adds the subcommand to `app`; the returned function runs it after parsing and returns
// the process exit code.
class MpiSession;

// Under mpirun (`mpi.distributed()`), the ranks share the samples and rank 0 writes the file.
std::function<int()> add_render_command(CLI::App& app, const MpiSession& mpi);

}  // namespace rtiow
