#pragma once
// What a render knows about its own noise, in the forms its users want: per-pixel
// variances of the mean, the statistics channels of an EXR, the mean sample count.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/film/image_error.h"
#include "core/io/image_output.h"
#include "core/render/render_settings.h"

namespace rtiow {

// The variance of each pixel's mean, per channel (infinite for a pixel with < 2 samples).
std::vector<Vec3d> pixel_mean_variances(const RenderResult& result);

// The film with its variances, for measure_error.
ImageEstimate to_estimate(const RenderResult& result);

// "spp" and "variance.R/G/B": the channels --stats-channels adds to an EXR.
std::vector<ExtraChannel> statistics_channels(const RenderResult& result);

// Every channel an image of the result carries beyond R, G, B: the statistics channels (where
// `statistics`), then the passes asked.
std::vector<ExtraChannel> image_channels(const RenderResult& result, bool statistics,
                                         const FirstHitPasses& passes);

double mean_samples(const RenderResult& result);

// Reads back an image written with statistics_channels(): the film and each pixel's variance
// of the mean. Nothing when the file is missing or unreadable, not `width` x `height`, lacks
// the channels, or does not carry every (key, value) of `required` as string metadata.
std::optional<ImageEstimate> read_statistics_image(
    const std::string& path, int width, int height,
    const std::vector<std::pair<std::string, std::string>>& required);

}  // namespace rtiow
