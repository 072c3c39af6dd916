#pragma once
// `rtiow render --summary-json FILE`: the render's summary for a script, in one documented
// schema (core/io/summary_json.h, docs/usage.md), where the line on stderr is for people.
// Written through the command's claim of FILE (core/io/output_claim.h) after the image, also
// when a signal or a time limit stopped the render.

#include <optional>
#include <string>

#include "core/render/denoised_output.h"

#include "core/render/render_job.h"
#include "core/render/render_settings.h"

namespace rtiow {

// The summary as JSON text. `ranks` is 1 outside mpirun; `exit_code` is the command's.
// `image_written`: false where a stopped render left the output as it was, its samples kept
// in the checkpoint alone ("output" is then null).
// `denoised`: what the denoiser delivered (--denoise), null otherwise.
std::string render_summary_json(const RenderJob& job, const RenderResult& result, int ranks,
                                int exit_code, bool image_written = true,
                                const std::optional<DenoiseFigures>& denoised = std::nullopt);

// The same summary's members of the render itself (without the command's schema, version,
// command, exit code and seconds), as one JSON object: what a library caller (the Python
// module's `summary`) reports, from the one writer. `output`: where the image went, or null.
std::string render_members_json(const std::string& scene, const RenderSettings& settings,
                                const RenderResult& result, const std::string* output,
                                const std::optional<DenoiseFigures>& denoised);

}  // namespace rtiow
