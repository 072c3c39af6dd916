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

struct ImageErrorEstimate {
  double error = 0.0;  // relative RMS, offset 0.01
  ErrorEstimate kind = ErrorEstimate::None;
  // The replicate ratios it was made with (RenderResult::replicate_ratios); none from one
  // sequence.
  std::shared_ptr<const std::vector<Vec3d>> replicate_ratios;
};

// The image's estimated error from the result's sums, as --image-error judges a round (each
// pixel's relative variance pooled from its neighbours, the mean over the image): calibrated
// with two replicates, an upper bound from one Sobol sequence's sample variance, none where a
// pixel has fewer than two samples. `threads` as RenderSettings::threads.
ImageErrorEstimate estimate_image_error(const RenderResult& result, int threads);

// "calibrated", "upper bound" or "none".
std::string to_string(ErrorEstimate kind);

// "image error 0.0123 estimated", "image error at most 0.0456", or "" when there is none.
std::string describe_error_estimate(ErrorEstimate kind, double estimated);
std::string describe_error_estimate(const RenderResult& result);

// Reads back an image written with statistics_channels(): the film and each pixel's variance
// of the mean. Nothing when the file is missing or unreadable, not `width` x `height`, lacks
// the channels, or does not carry every (key, value) of `required` as string metadata.
std::optional<ImageEstimate> read_statistics_image(
    const std::string& path, int width, int height,
    const std::vector<std::pair<std::string, std::string>>& required);

}  // namespace rtiow
