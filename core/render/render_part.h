#pragma once
// A share of a render, in a file: the samples [first, first + count) of every pixel, kept as
// their exact sums so that shares rendered anywhere merge into the bits of one render.
//
// The file is an OpenEXR image: R, G, B hold the share's own mean (so it can be looked at),
// and 32-bit unsigned channels {sum,odd,squares}.{R,G,B}.{0..3} hold the 128-bit sums of the
// samples and of the spread the variances need (core/film/pixel_variance.h; a part written
// before parts kept spreads has sum.* alone, and merges without variances); a part rendered
// with --passes adds first_hit.{albedo.R,...,Z}.{0..3}, the 128-bit signed sums the passes are
// the mean of (core/film/first_hit_sum.h). Metadata names
// the samples held and the digest of what its render's shares have in common
// (core/render/render_identity.h), which merging checks.

#include <cstdint>
#include <string>
#include <vector>

#include "core/film/pixel_sums.h"
#include "core/io/image_output.h"
#include "core/render/render_settings.h"
#include "core/scene/scene.h"

namespace rtiow {

struct RenderPart {
  std::string path;
  int width = 0, height = 0;
  std::uint64_t first_sample = 0, samples = 0;
  std::uint64_t job_samples = 0;  // the whole job's samples per pixel, so a missing share shows
  std::string digest;             // shared_digest(): what every share of its render has
  Metadata metadata;              // everything else the part recorded (scene, seed, rays...)
  // Spreads empty in a part written without them, first hits in one rendered without passes.
  PixelSums sums;
};

// A share's result as a part file keeps it: `share` the settings it was rendered with (its
// first sample and count), `job_samples` the whole job's samples per pixel, `metadata` what the
// render records (render_metadata.h). The sums are copied: the result keeps them.
RenderPart make_part(const Scene& scene, const RenderSettings& share, std::uint64_t job_samples,
                     const RenderResult& result, Metadata metadata);

// Writes a share atomically. `path` must end in .exr.
void write_part(const std::string& path, const RenderPart& part);

// Reads a share; throws InvalidInput naming the file (and the field) when it is not one:
// every header field is checked before the pixels are allocated.
RenderPart read_part(const std::string& path);

class ImageReader;  // core/io/image_file.h

// The same from an image already opened (`path` names it in messages): what the fuzz target
// drives with headers and pixels of its own making.
RenderPart read_part(ImageReader& in, const std::string& path);

struct MergedRender {
  Film film;
  std::uint64_t samples = 0;
  Metadata metadata;  // the parts' common metadata, with spp and rays_traced totalled
  // Spreads empty unless every part had its spread; first hits unless every part had them.
  PixelSums sums;
  FirstHitPasses passes;  // the passes the parts were rendered with
};

// The merged render as one render's result (samples from index 0, drawn by `sampler`), for
// its variances (core/render/render_statistics.h).
RenderResult merged_result(const MergedRender& merged, SamplerKind sampler, int replicates);

// Checks that the parts belong to one render (same digest, size and job), that they neither
// overlap nor leave a gap from sample 0 to the job's last, and adds them; with the passes they
// recorded (rtiow:passes) when every part holds their sums. Throws InvalidInput
// naming the files at fault.
MergedRender merge_parts(const std::vector<RenderPart>& parts);

}  // namespace rtiow
