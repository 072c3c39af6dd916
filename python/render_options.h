#pragma once
// The keyword arguments of rtiow.render(), read into the library's RenderRequest: each is one
// of `rtiow render`'s long options with underscores (--time-limit is time_limit), with the
// value the option takes (a string, a number, a bool for a flag; a sequence where the option
// takes a comma-separated list). An unknown name or a value of the wrong kind is refused with
// InvalidInput naming it (a ValueError in Python).

#include <pybind11/pybind11.h>

#include "core/render/render_request.h"

namespace rtiow::python {

struct ParsedOptions {
  RenderRequest request;
};

ParsedOptions parse_render_options(const pybind11::kwargs& options);

}  // namespace rtiow::python
