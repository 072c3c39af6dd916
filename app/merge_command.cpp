#include "app/merge_command.h"

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/render/part_merge.h"
#include "core/render/render_statistics.h"
#include "core/session/merge_summary.h"
#include "core/session/work_display.h"

namespace rtiow {

int run_merge(const MergeOptions& o) {
  // The summary's path is checked and claimed before the parts are read, as the image's is.
  std::optional<OutputClaim> summary_claim;
  if (!o.summary_json.empty()) {
    std::vector<std::string> inputs = o.parts;
    inputs.push_back(o.output);  // nor may it be the image
    check_output_path(o.summary_json, inputs, "--summary-json");
    summary_claim.emplace(o.summary_json);
  }
  MergeRequest request;
  request.statistics = o.stats_channels, request.denoise = o.denoise, request.threads = o.threads;
  WorkProgress reading, denoising;
  std::optional<WorkDisplay> display;
  if (!o.quiet) {
    request.reading = &reading;
    request.denoising = &denoising;
    display.emplace(
        std::vector<WorkPhase>{{&reading, "of the parts read"}, {&denoising, "denoised"}});
  }
  const MergedImage merged = merge_to_file(o.parts, o.output, request);
  display.reset();  // its live line erased before the lines below
  // (Denoised, the passes were the denoiser's to follow: an image without them is what was asked.)
  if (merged.passes.any() && !merged.passes_kept && !o.denoise) {
    std::fprintf(stderr,
                 "rtiow: warning: the parts hold the passes %s, which %s cannot: merge to .exr "
                 "to keep them\n",
                 to_string(merged.passes).c_str(), quote_value(o.output).c_str());
  }
  if (!o.quiet) {
    const std::string error =
        describe_error_estimate(merged.error_estimate, merged.estimated_error);
    std::fprintf(stderr, "merged %zu part%s: %dx%d, %llu spp%s%s -> %s\n", merged.parts,
                 merged.parts == 1 ? "" : "s", merged.film.width(), merged.film.height(),
                 static_cast<unsigned long long>(merged.samples),
                 error.empty() ? "" : (", " + error).c_str(),
                 merged.passes_kept ? (", passes " + to_string(merged.passes)).c_str() : "",
                 one_line(o.output).c_str());
    if (merged.denoised) {
      std::fprintf(stderr, "%s\n", describe(*merged.denoised).c_str());
    }
  }
  if (!o.summary_json.empty()) {
    write_text_atomically(o.summary_json,
                          merge_summary_json(o.command, o.parts, o.output, merged, o.threads));
  }
  return 0;
}

}  // namespace rtiow
