#pragma once
// `rtiow merge --summary-json FILE` and `rtiow denoise --summary-json FILE`: what their lines say,
// for a script (a render farm reading the merged frame's error and the denoiser's figures), in the
// schema every command's summary shares (core/io/summary_json.h, docs/usage.md). Written through
// the command's claim of FILE after the image; not written when the merge fails.

#include <string>
#include <vector>

#include "core/render/part_merge.h"

namespace rtiow {

// The summary as JSON text: `command` is "merge" or "denoise", `parts` the files read, `output`
// the image written, `threads` the count asked (0: every core).
std::string merge_summary_json(const std::string& command, const std::vector<std::string>& parts,
                               const std::string& output, const MergedImage& merged, int threads);

}  // namespace rtiow
