// The sample loop of the renderer's own accelerators, compiled for each instruction set
// (core/parallel/instruction_sets.h); any other accelerator (the benchmark's recording one)
// gets the template's loop as it is.

#include "core/accel/embree_accel.h"
#include "core/accel/naive_accel.h"
#include "core/parallel/instruction_sets.h"
#include "core/render/render_loop.h"

namespace rtiow {

RTIOW_DISPATCHED std::uint64_t accumulate_run_dispatched(const RenderContext<EmbreeAccel>& ctx,
                                                         const PixelRun& run, RunAccumulators out) {
  return accumulate_run_inlined(ctx, run, out);
}

RTIOW_DISPATCHED std::uint64_t accumulate_run_dispatched(const RenderContext<NaiveAccel>& ctx,
                                                         const PixelRun& run, RunAccumulators out) {
  return accumulate_run_inlined(ctx, run, out);
}

}  // namespace rtiow
