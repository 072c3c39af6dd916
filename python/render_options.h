#pragma once
// The keyword arguments of rtiow.render(), read into the library's RenderRequest: each is one
// of `rtiow render`'s long options with underscores (--time-limit is time_limit), with the
// value the option takes (a string, a number, a bool for a flag; a sequence where the option
// takes a comma-separated list). An unknown name or a value of the wrong kind is refused with
// InvalidInput naming it (a ValueError in Python).

#include <pybind11/pybind11.h>

#include <string>

#include "core/render/render_job.h"
#include "core/session/render_session.h"

namespace rtiow::python {

struct ParsedOptions {
  // The request (job.request), a share of the samples (job.part as --part "i/n" or
  // job.sample_range as --sample-range "A:B", at most one: the render is then a part file,
  // which rtiow.merge() or rtiow merge adds up) and the output (job.output, where given).
  JobRequest job;
  // What goes around a render to a file, as rtiow render -o has it: the checkpoint (resume,
  // restart, keep_state, checkpoint), preview, display, reproducible.
  SessionOptions session;
};

ParsedOptions parse_render_options(const pybind11::kwargs& options);

}  // namespace rtiow::python
