#pragma once
// The passes a render can write beside its image (--passes albedo,normal,depth): each the mean
// over the pixel's samples of what its camera ray first met (core/film/first_hit_sum.h), as EXR
// channels named the way compositors and denoisers look for them: albedo.R/G/B, N.X/Y/Z and Z.
// Where a sample saw the sky all three are 0 (no surface: no colour, no normal, no distance), so
// a pixel on a silhouette holds its surface's values weighted by the share of samples that met it.

#include <string>
#include <vector>

#include "core/io/image_output.h"

namespace rtiow {

struct FirstHitPasses {
  bool albedo = false, normal = false, depth = false;

  bool any() const { return albedo || normal || depth; }
  bool operator==(const FirstHitPasses&) const = default;
};

// "albedo,normal,depth" (the ones asked, in that order), or "none".
std::string to_string(const FirstHitPasses& passes);

// From a comma-separated list of pass names ("albedo,depth"; "none" for no pass). Throws
// InvalidInput naming an unknown pass or one given twice.
FirstHitPasses parse_passes(const std::string& list);

// The names --passes takes, for help texts: "albedo, normal, depth".
std::string pass_names();

// The names of the channels of the passes asked, in the order pass_channels() gives them.
std::vector<std::string> pass_channel_names(const FirstHitPasses& passes);

struct RenderResult;  // core/render/render_settings.h

// The channels of the passes asked, from the result's first-hit sums and sample counts.
std::vector<ExtraChannel> pass_channels(const RenderResult& result, const FirstHitPasses& passes);

}  // namespace rtiow
