#pragma once
// The members that a render's and a merge's --summary-json share (docs/usage.md, "A summary for
// scripts"), each written by one function, so that a key means the same wherever it appears: the
// samples per pixel, the passes written, the image's estimated error and the denoiser's figures.

#include <cstdint>
#include <functional>
#include <optional>

#include "core/io/json_writer.h"
#include "core/render/denoised_output.h"
#include "core/render/first_hit_passes.h"
#include "core/render/render_settings.h"

namespace rtiow {

// "spp": {"least", "most", "mean", "asked"} (`asked` null where nothing was).
void write_spp_member(JsonWriter& j, std::uint64_t least, std::uint64_t most, double mean,
                      std::optional<int> asked);

// "passes": the passes written beside the image, ["albedo", "normal", "depth"] or fewer.
void write_passes_member(JsonWriter& j, const FirstHitPasses& written);

// "error": {"estimated", "estimate", "target"}: the image's estimated relative RMS error (null
// where `kind` is none), what that estimate is worth, and the target, which `target` writes (the
// writer at its value).
void write_error_member(JsonWriter& j, ErrorEstimate kind, double estimated,
                        const std::function<void(JsonWriter&)>& target);

// "denoise": {"estimated_error", "noisy_error", "seconds"}, or null where nothing was denoised.
void write_denoise_member(JsonWriter& j, const std::optional<DenoiseFigures>& denoised);

}  // namespace rtiow
