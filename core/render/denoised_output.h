#pragma once
// A render's result as `--denoise` delivers it: the denoised image, the figures the summary,
// the metadata and --summary-json report, and the channels an EXR keeps beside it (the noisy
// image and the denoiser's own estimate of each pixel's error). One call for every place that
// denoises: a render's write, a merge of parts, `rtiow denoise`.

#include <string>
#include <vector>

#include "core/denoise/denoise_input.h"
#include "core/denoise/denoiser.h"
#include "core/film/film.h"
#include "core/film/pixel_sums.h"
#include "core/io/image_output.h"

namespace rtiow {

struct RenderResult;
struct RenderSettings;

struct DenoiseFigures {
  double estimated_error = 0.0;  // the denoised image's relative RMS error (offset 0.01)
  double noisy_error = 0.0;      // the noisy image's, by the same estimate from the halves
  double seconds = 0.0;          // the denoiser's own time
};

DenoiseFigures figures_of(const DenoisedImage& denoised);

// "denoised in 1.32 s: image error 0.0660 estimated (the noisy image 0.0966 by the same
// estimate)": the summary's line. The noisy image's figure is the denoiser's estimate from the
// halves, beside its own; the render's line before it gives the render's pooled one.
std::string describe(const DenoiseFigures& figures);

struct DenoisedOutput {
  Film image;
  DenoiseFigures figures;
  std::vector<ExtraChannel> channels;  // noisy.R/G/B, denoise.mse.R/G/B, denoise.kept
};

// The sums a denoiser reads: a render's result, or a render's state between its rounds.
struct DenoiseSource {
  const PixelSums& sums;
  const std::vector<std::uint32_t>& samples;
  std::uint64_t first_sample = 0;
  int replicates = 0;
  int width = 0, height = 0;
};

// The halves and features of a render's sums. Throws InvalidInput naming what they lack: the
// odd samples' sums (a render that kept one sequence), the first hits' sums (no passes), or a
// pixel with fewer than one sample in each half.
DenoiseInput denoise_input(const DenoiseSource& source);
DenoiseInput denoise_input(const RenderResult& result);

// Why the sums cannot be denoised (what denoise_input() would refuse), or empty.
std::string why_not_denoised(const DenoiseSource& source);
std::string why_not_denoised(const RenderResult& result);

// A denoised error target's estimate is the image it delivers: where the render ended between
// judgements (its time limit, a stop), the denoiser's image of the finished sums, `denoised`,
// gives the render its estimate, for the summary, the metadata and --summary-json to report.
// Nothing for any other render.
void take_delivered_estimate(const RenderSettings& settings, RenderResult& result,
                             const DenoisedImage& denoised);

// The denoised image of `result`: its last judgement's where an image-error target judged
// these very sums denoised (RenderResult::denoised), else the denoiser's (core/denoise/
// denoiser.h) now. Throws as denoise_input() and denoise() do; `control` as denoise() takes it.
DenoisedImage denoised_image(const RenderResult& result, const DenoiseControl& control = {});

// The denoised image to write (denoised_image(), or the denoiser's of a merge), its figures
// recorded in `metadata`; the channels only where `extra_channels` (the output can hold them).
DenoisedOutput denoised_output(DenoisedImage denoised, bool extra_channels, Metadata& metadata);

}  // namespace rtiow
