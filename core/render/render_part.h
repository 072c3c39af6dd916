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
#include "core/parallel/work_progress.h"
#include "core/render/render_settings.h"
#include "core/scene/scene.h"

namespace rtiow {

// A part file's header: which share of which render it holds. Its sums travel beside it (the
// result's when written, the merge's total when read), never copied into it.
struct RenderPart {
  std::string path;
  int width = 0, height = 0;
  std::uint64_t first_sample = 0, samples = 0;
  std::uint64_t job_samples = 0;  // the whole job's samples per pixel, so a missing share shows
  std::string digest;             // shared_digest(): what every share of its render has
  Metadata metadata;              // everything else the part recorded (scene, seed, rays...)
};

// A share's header as a part file keeps it: `share` the settings it was rendered with (its
// first sample and count), `job_samples` the whole job's samples per pixel, `metadata` what the
// render records (render_metadata.h). Throws InvalidInput unless `result` is of the share's film.
RenderPart make_part(const Scene& scene, const RenderSettings& share, std::uint64_t job_samples,
                     const RenderResult& result, Metadata metadata);

// Writes a share and its sums (`result.sums` of make_part's result: the spreads and first hits
// where kept) atomically, encoded a strip of rows at a time. `path` must end in .exr.
void write_part(const std::string& path, const RenderPart& part, const PixelSums& sums);

struct MergedRender {
  Film film;
  std::uint64_t samples = 0;
  Metadata metadata;  // the parts' common metadata, with spp and rays_traced totalled
  // Spreads empty unless every part had its spread; first hits unless every part had them.
  PixelSums sums;
  FirstHitPasses passes;        // the passes the parts were rendered with
  std::string without_spreads;  // the first part given that keeps no spreads ("" if none)
};

// The merged render as one render's result (samples from index 0, drawn by `sampler`), for
// its variances (core/render/render_statistics.h); its film and sums are moved, not copied.
RenderResult merged_result(MergedRender&& merged, SamplerKind sampler, int replicates);

class ImageReader;  // core/io/image_file.h

// Parts read one at a time and added, so that a merge holds their total and one part's words
// however many parts it is given. Each part's header is checked against the first's (the same
// render: digest, size, job and rtiow; the same passes, whose sums it must hold) before its
// pixels are read, and each pixel's sums as a checkpoint's are; finish() checks that the parts
// tile the job, from sample 0 to its last, without overlap. Throws InvalidInput naming the
// files at fault.
class PartMerge {
 public:
  // What each part counts in a progress of the parts read, its rows a share of it as they are.
  static constexpr std::uint64_t kPartWork = 1'000'000;

  // With `reading`, whose total the caller begins at kPartWork a part, the rows read are counted
  // in it (a 4K part takes seconds to read).
  explicit PartMerge(WorkProgress* reading = nullptr) : reading_(reading) {}

  void add(const std::string& path);
  // The same from an image already opened (`path` names it in messages): what the fuzz
  // target drives with headers and pixels of its own making.
  void add(ImageReader& in, const std::string& path);
  // The parts added as one render, with the passes they recorded where every part holds
  // their sums, and the spreads where every part keeps them.
  MergedRender finish() &&;

 private:
  std::vector<RenderPart> parts_;  // the headers read; their sums are in the total
  MergedRender merged_;
  WorkProgress* reading_ = nullptr;
};

}  // namespace rtiow
