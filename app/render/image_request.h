#pragma once
// `rtiow render --like IMAGE`: which parts of the image's recorded request
// (core/render/recorded_request.h) the user's options replace.

#include <CLI/CLI.hpp>

#include <set>

#include "core/render/recorded_request.h"

namespace rtiow {

// The parts of a request the user gave an option of on the `render` command line.
std::set<RequestPart> parts_given(CLI::App& render);

// Whether the render's output keeps channels beyond R, G and B (an .exr).
bool output_holds_channels(CLI::App& render);

}  // namespace rtiow
