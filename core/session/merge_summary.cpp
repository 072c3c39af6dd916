#include "core/session/merge_summary.h"

#include "core/io/summary_json.h"
#include "core/parallel/thread_count.h"
#include "core/session/summary_members.h"

namespace rtiow {

std::string merge_summary_json(const std::string& command, const std::vector<std::string>& parts,
                               const std::string& output, const MergedImage& merged, int threads) {
  JsonWriter j = begin_summary(command, 0);
  j.key("output").string(output);
  j.key("parts").begin_array();
  for (const std::string& part : parts) j.string(part);
  j.end();
  // The frame's size, and the region the parts hold where they are a crop's (as render says them).
  const FramePlacement& at = merged.placement;
  const int width = merged.film.width(), height = merged.film.height();
  j.key("width").whole(at.whole() ? width : at.frame_width);
  j.key("height").whole(at.whole() ? height : at.frame_height);
  j.key("crop");
  if (at.whole()) {
    j.null();
  } else {
    j.begin_array().whole(at.x).whole(at.y).whole(at.x + width).whole(at.y + height).end();
  }
  write_passes_member(j, merged.passes_kept ? merged.passes : FirstHitPasses{});
  j.key("threads").whole(thread_count(threads));
  // Every pixel of a merge holds the whole job's samples; no count was asked of the merge.
  write_spp_member(j, merged.samples, merged.samples, double(merged.samples), std::nullopt);
  write_error_member(j, merged.error_estimate, merged.estimated_error,
                     [](JsonWriter& w) { w.null(); });
  write_denoise_member(j, merged.denoised);
  return summary_text(j);
}

}  // namespace rtiow
