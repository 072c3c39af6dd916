#include "core/render/part_merge.h"

#include <new>
#include <utility>

#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/limits/setting_name.h"
#include "core/render/render_metadata.h"
#include "core/render/render_part.h"
#include "core/render/render_statistics.h"
#include "core/sampling/sampler.h"

namespace rtiow {
namespace {

// The sampler and the replicates the parts record.
std::pair<std::string, std::int64_t> recorded_sampling(const MergedRender& merged) {
  std::string sampler;
  std::int64_t replicates = kReplicates;  // an older rtiow's parts always had two
  for (const auto& [key, value] : merged.metadata) {
    if (const auto* text = std::get_if<std::string>(&value); key == metadata_key::kSampler && text)
      sampler = *text;
    if (const auto* n = std::get_if<std::int64_t>(&value); key == metadata_key::kReplicates && n)
      replicates = *n;
  }
  return {sampler, replicates};
}

// The merged image's estimated error, recorded as one render's is: from the sums of every
// part (a part records its share's alone, which the merged metadata leaves out). None where
// the parts keep no spreads or record no sampler this rtiow knows. Returns the replicate ratios
// it was made with (none from one sequence), which the variance channels take too.
std::shared_ptr<const std::vector<Vec3d>> record_error_estimate(const MergedRender& merged,
                                                                Metadata& metadata) {
  if (!merged.sums.keeps(SumGroup::Odd)) return {};
  const auto [sampler, replicates] = recorded_sampling(merged);
  RenderResult whole;
  try {
    whole = merged_result(merged, parse_sampler(sampler), replicates > 1 ? kReplicates : 1);
  } catch (const InvalidInput&) {
    return {};
  } catch (const std::bad_alloc&) {
    return {};  // a copy of the sums does not fit beside them: no estimate, the merge goes on
  }
  const ImageErrorEstimate estimate = estimate_image_error(whole, 0);
  if (estimate.kind == ErrorEstimate::None) return {};
  metadata.emplace_back(metadata_key::kEstimatedImageError, estimate.error);
  metadata.emplace_back(metadata_key::kErrorEstimate, to_string(estimate.kind));
  return estimate.replicate_ratios;
}

// The spp and variance channels of the merged render, as one render's --stats-channels.
std::vector<ExtraChannel> merged_statistics(
    const MergedRender& merged, const std::vector<RenderPart>& parts,
    const std::shared_ptr<const std::vector<Vec3d>>& replicate_ratios) {
  if (!merged.sums.keeps(SumGroup::Odd)) {
    for (const RenderPart& p : parts) {
      if (!p.sums.keeps(SumGroup::Odd)) {
        throw InvalidInput(setting("stats_channels") + ": part file " +
                           quote_value(p.path, kWholePath) +
                           " holds no spreads (an older rtiow wrote it): render it again");
      }
    }
  }
  const auto [sampler, replicates] = recorded_sampling(merged);
  if (replicates != 1 && replicates != kReplicates) {
    throw InvalidInput(setting("stats_channels") + ": the parts record " +
                       std::string(kMetadataPrefix) + metadata_key::kReplicates + " " +
                       std::to_string(replicates) + ": a render draws one sequence or " +
                       std::to_string(kReplicates) + " replicates");
  }
  if (replicates != kReplicates && sampler != to_string(SamplerKind::Independent)) {
    throw InvalidInput(setting("stats_channels") +
                       ": the parts were rendered from one sequence, which keeps no estimate of "
                       "the error: render them with " +
                       setting("stats_channels"));
  }
  try {
    RenderResult whole = merged_result(merged, parse_sampler(sampler), int(replicates));
    whole.replicate_ratios = replicate_ratios;  // of these sums, where the estimate made them
    return statistics_channels(whole);
  } catch (const InvalidInput& e) {
    throw InvalidInput(setting("stats_channels") + ": the parts' sampler: " + e.what());
  }
}

// The merged render as the denoiser reads it: its halves need the parts' two replicates.
RenderResult merged_for_denoising(const MergedRender& merged) {
  const auto [sampler, replicates] = recorded_sampling(merged);
  if (replicates != kReplicates || !merged.sums.keeps(SumGroup::Odd) ||
      !merged.sums.keeps(SumGroup::FirstHit)) {
    throw InvalidInput(setting("denoise") +
                       ": the parts keep no independent halves or first hits to denoise with: "
                       "render them with " +
                       setting("denoise"));
  }
  try {
    return merged_result(merged, parse_sampler(sampler), kReplicates);
  } catch (const InvalidInput& e) {
    throw InvalidInput(setting("denoise") + ": the parts' sampler: " + e.what());
  }
}

}  // namespace

MergedImage merge_part_files(const std::vector<std::string>& paths, const MergeRequest& request) {
  std::vector<RenderPart> parts;
  for (const std::string& path : paths) parts.push_back(read_part(path));
  MergedRender merged = merge_parts(parts);
  MergedImage image;
  image.metadata = merged.metadata;
  const auto replicate_ratios = record_error_estimate(merged, image.metadata);
  if (request.statistics) image.channels = merged_statistics(merged, parts, replicate_ratios);
  image.passes = merged.passes;
  image.passes_kept = merged.passes.any() && request.extra_channels;
  if (image.passes_kept) {
    const RenderResult whole = merged_result(merged, SamplerKind::Independent, kReplicates);
    for (ExtraChannel& c : pass_channels(whole, merged.passes))
      image.channels.push_back(std::move(c));
  }
  image.placement = recorded_placement(image.metadata, "part " + quote_value(paths.front()),
                                       merged.film.width(), merged.film.height());
  if (!image.passes_kept) {
    std::erase_if(image.metadata,
                  [](const auto& entry) { return entry.first == metadata_key::kPasses; });
  }
  if (request.denoise) {
    DenoisedOutput denoised = denoised_output(merged_for_denoising(merged), request.extra_channels,
                                              image.metadata, request.cancelled);
    image.channels.insert(image.channels.begin(),
                          std::make_move_iterator(denoised.channels.begin()),
                          std::make_move_iterator(denoised.channels.end()));
    image.denoised = denoised.figures;
    merged.film = std::move(denoised.image);
  }
  image.film = std::move(merged.film);
  image.samples = merged.samples;
  image.parts = parts.size();
  return image;
}

MergedImage merge_to_file(const std::vector<std::string>& paths, const std::string& output,
                          MergeRequest request) {
  check_image_output(output, paths);
  const ImageFormat* format = image_format(output);
  request.extra_channels = format && format->extra_channels;
  if (request.statistics && !request.extra_channels) {
    throw InvalidInput(setting("stats_channels") + ": output " + quote_value(output) +
                       " must be .exr to hold the spp and variance channels");
  }
  const OutputClaim claim(output);  // before the parts are read: a second writer is refused now
  MergedImage merged = merge_part_files(paths, request);
  write_image(output, merged.film, merged.metadata, merged.channels, merged.placement);
  return merged;
}

}  // namespace rtiow
