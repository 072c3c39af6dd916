#include "app/merge_command.h"

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "core/io/image_output.h"
#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/render/part_merge.h"

namespace rtiow {

int run_merge(const MergeOptions& o) {
  check_image_output(o.output, o.parts);
  const ImageFormat* format = image_format(o.output);
  if (o.stats_channels && format && !format->extra_channels) {
    throw InvalidInput("--stats-channels: output " + quote_value(o.output) +
                       " must be .exr to hold the spp and variance channels");
  }
  const OutputClaim claim(o.output);  // before the parts are read: a second writer is refused now
  const MergedImage merged =
      merge_part_files(o.parts, {o.stats_channels, format && format->extra_channels, o.denoise});
  if (merged.passes.any() && !merged.passes_kept) {
    std::fprintf(stderr,
                 "rtiow: warning: the parts hold the passes %s, which %s cannot: merge to .exr "
                 "to keep them\n",
                 to_string(merged.passes).c_str(), quote_value(o.output).c_str());
  }
  write_image(o.output, merged.film, merged.metadata, merged.channels, merged.placement);
  if (!o.quiet) {
    std::fprintf(stderr, "merged %zu parts: %dx%d, %llu spp%s -> %s\n", merged.parts,
                 merged.film.width(), merged.film.height(),
                 static_cast<unsigned long long>(merged.samples),
                 merged.passes_kept ? (", passes " + to_string(merged.passes)).c_str() : "",
                 one_line(o.output).c_str());
    if (merged.denoised) {
      std::fprintf(stderr, "denoised in %.2f s: image error %.4f estimated (noisy %.4f)\n",
                   merged.denoised->seconds, merged.denoised->estimated_error,
                   merged.denoised->noisy_error);
    }
  }
  return 0;
}

}  // namespace rtiow
