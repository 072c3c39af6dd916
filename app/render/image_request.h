#pragma once
// `rtiow render --like IMAGE`: which parts of the image's recorded request
// (core/render/recorded_request.h) the user's options replace.

#include <functional>
#include <set>
#include <string>

#include "core/render/recorded_request.h"

namespace rtiow {

// The parts of a request the user gave an option of on the `render` command line, from
// whether each option ("--spp", "scene_file") was typed.
std::set<RequestPart> parts_given(const std::function<bool(const std::string& option)>& typed);

}  // namespace rtiow
