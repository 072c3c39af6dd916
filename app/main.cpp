// rtiow: the command line. Parses, dispatches to a subcommand, and turns every refusal
// into one line on stderr with exit code 2 (bad input) or 1 (a failure while working).

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <functional>
#include <vector>

#include "app/accuracy_command.h"
#include "app/bench_command.h"
#include "app/merge_command.h"
#include "app/mpi_session.h"
#include "app/render_command.h"
#include "app/scene_command.h"
#include "core/error.h"

int main(int argc, char** argv) {
  const rtiow::MpiSession mpi(argc, argv);
  CLI::App app{
      "rtiow: a path tracer for the scenes of Ray Tracing in One Weekend, "
      "built on Embree, oneTBB and OpenImageIO",
      "rtiow"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "rtiow 0.1.0");
  std::vector<std::function<int()>> commands{
      rtiow::add_render_command(app, mpi), rtiow::add_scene_command(app),
      rtiow::add_merge_command(app), rtiow::add_bench_command(app),
      rtiow::add_accuracy_command(app)};

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "rtiow: error: %s (see rtiow --help)\n", e.what());
    return 2;
  }

  try {
    for (const auto& command : commands) {
      const int code = command();
      if (code >= 0) return code;
    }
  } catch (const rtiow::InvalidInput& e) {
    // Bad input is seen alike by every rank before any work: say it once, all exit.
    if (mpi.rank() == 0) std::fprintf(stderr, "rtiow: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    if (mpi.distributed()) {
      std::fprintf(stderr, "rtiow: error on rank %d of %d: %s\n", mpi.rank(), mpi.size(), e.what());
      mpi.abort(1);  // the other ranks may be waiting for this one
    }
    std::fprintf(stderr, "rtiow: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
