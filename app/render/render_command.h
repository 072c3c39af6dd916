#pragma once
// `rtiow render`: options, validation before any work, the render, and the output file.

#include <set>

#include "app/render/render_options.h"
#include "core/render/recorded_request.h"

namespace rtiow {

class MpiSession;

// The render command as parsed: its options and what the user typed of them.
struct RenderCommand {
  RenderOptions options;
  bool scene_named = false;   // --scene was given
  bool output_given = false;  // -o was given
  // With --like: the parts of the request the typed options replace, and whether the output
  // keeps channels beyond R, G and B.
  std::set<RequestPart> typed;
  bool output_holds_channels = false;
};

// Under mpirun (`mpi.distributed()`), the ranks share the samples and rank 0 writes the file;
// the process exit code.
int run_render_command(const RenderCommand& command, const MpiSession& mpi);

}  // namespace rtiow
