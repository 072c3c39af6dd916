#pragma once
// The keyword arguments of rtiow.render(), read into the library's RenderRequest: each is one
// of `rtiow render`'s long options with underscores (--time-limit is time_limit), with the
// value the option takes (a string, a number, a bool for a flag; a sequence where the option
// takes a comma-separated list). An unknown name or a value of the wrong kind is refused with
// InvalidInput naming it (a ValueError in Python).

#include <pybind11/pybind11.h>

#include <string>

#include "core/render/render_request.h"

namespace rtiow::python {

struct ParsedOptions {
  RenderRequest request;
  // A share of the samples (as --part "i/n" or --sample-range "A:B"), at most one: the render
  // is then written as a part file, which rtiow.merge() (or rtiow merge) adds up.
  std::string part, sample_range;
};

ParsedOptions parse_render_options(const pybind11::kwargs& options);

}  // namespace rtiow::python
