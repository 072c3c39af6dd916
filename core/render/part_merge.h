#pragma once
// Merging part files into the image one render of all their samples gives, as a library call:
// `rtiow merge` is this and a write. The parts are read and checked (core/render/render_part.h:
// one render, tiling the job, every pixel's sums possible), added, and given the channels the
// output can hold: the statistics a single render's --stats-channels writes, and the passes
// the parts were rendered with.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/film/film.h"
#include "core/io/image_output.h"
#include "core/parallel/work_progress.h"
#include "core/render/denoised_output.h"
#include "core/render/first_hit_passes.h"
#include "core/render/render_settings.h"

namespace rtiow {

struct MergeRequest {
  bool statistics = false;     // the spp and variance channels (--stats-channels)
  bool extra_channels = true;  // the output holds channels beyond R, G, B (EXR)
  bool denoise = false;        // the image denoised (core/denoise/denoised_output.h)
  int threads = 0;             // the merge's and the denoiser's, 0: every core (--threads)
  // Asked while denoising: once true, the merge throws DenoiseCancelled and writes nothing.
  std::function<bool()> cancelled;
  // For a display: the parts read (PartMerge's progress) and the denoiser's work.
  WorkProgress* reading = nullptr;
  WorkProgress* denoising = nullptr;
};

struct MergedImage {
  Film film;
  Metadata metadata;                   // the parts' common metadata, spp and rays totalled
  std::vector<ExtraChannel> channels;  // statistics where asked, then the passes kept
  FramePlacement placement;            // where a crop's parts lie in the frame
  std::uint64_t samples = 0;           // per pixel, the whole job's
  std::size_t parts = 0;
  FirstHitPasses passes;                   // the passes the parts hold
  bool passes_kept = false;                // false: the output cannot hold them (they are left out)
  std::optional<DenoiseFigures> denoised;  // what the denoiser delivered, where asked
  // The merged sums' estimated error (relative RMS, offset 0.01) and what it is worth (None where
  // the parts keep no estimate): describe_error_estimate() says it as a render's line does.
  double estimated_error = 0.0;
  ErrorEstimate error_estimate = ErrorEstimate::None;
};

// Reads the part files at `paths` and merges them. Throws InvalidInput naming the file and
// what is wrong: not a part, parts of different renders, overlapping or missing samples, sums
// no samples can add up to, statistics asked of parts that keep no spreads (or were rendered
// from one sequence), a thread count out of range. Runs on request.threads threads.
MergedImage merge_part_files(const std::vector<std::string>& paths, const MergeRequest& request);

// `rtiow merge` and `rtiow denoise` whole: the output checked against the parts and claimed
// before they are read, the merge, and the image written with what its format can hold.
// `request.extra_channels` is taken from the output's format. Returns what was written.
MergedImage merge_to_file(const std::vector<std::string>& paths, const std::string& output,
                          MergeRequest request);

}  // namespace rtiow
