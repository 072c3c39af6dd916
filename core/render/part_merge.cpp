#include "core/render/part_merge.h"

#include <new>
#include <utility>

#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/limits/setting_name.h"
#include "core/parallel/thread_count.h"
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

// The sampler the parts record, or the reason it is none this rtiow knows.
struct RecordedSampler {
  std::optional<SamplerKind> kind;
  std::string unknown;  // why not, where kind is empty
};

RecordedSampler parse_recorded_sampler(const std::string& name) {
  try {
    return {parse_sampler(name), {}};
  } catch (const InvalidInput& e) {
    return {std::nullopt, e.what()};
  }
}

// The merged image's estimated error, recorded as one render's is: from the sums of every
// part (a part records its share's alone, which the merged metadata leaves out), in `whole`
// and its metadata. None where the parts keep no spreads or record no sampler this rtiow
// knows. Returns the replicate ratios it was made with (none from one sequence), which the
// variance channels take too.
std::shared_ptr<const std::vector<Vec3d>> record_error_estimate(RenderResult& whole,
                                                                const RecordedSampler& sampler,
                                                                Metadata& metadata) {
  if (!whole.sums.keeps(SumGroup::Odd) || !sampler.kind) return {};
  ImageErrorEstimate estimate;
  try {
    estimate = estimate_image_error(whole, 0);
  } catch (const std::bad_alloc&) {
    return {};  // its buffers do not fit beside the sums: no estimate, the merge goes on
  }
  if (estimate.kind == ErrorEstimate::None) return {};
  whole.estimated_image_error = estimate.error, whole.error_estimate = estimate.kind;
  metadata.emplace_back(metadata_key::kEstimatedImageError, estimate.error);
  metadata.emplace_back(metadata_key::kErrorEstimate, to_string(estimate.kind));
  return estimate.replicate_ratios;
}

// The spp and variance channels of the merged render, as one render's --stats-channels.
std::vector<ExtraChannel> merged_statistics(const RenderResult& whole,
                                            const std::string& without_spreads,
                                            const RecordedSampler& sampler,
                                            std::int64_t replicates) {
  if (!without_spreads.empty()) {
    throw InvalidInput(setting("stats_channels") + ": part file " +
                       quote_value(without_spreads, kWholePath) +
                       " holds no spreads (an older rtiow wrote it): render it again");
  }
  if (replicates != 1 && replicates != kReplicates) {
    throw InvalidInput(setting("stats_channels") + ": the parts record " +
                       std::string(kMetadataPrefix) + metadata_key::kReplicates + " " +
                       std::to_string(replicates) + ": a render draws one sequence or " +
                       std::to_string(kReplicates) + " replicates");
  }
  if (replicates != kReplicates && sampler.kind != SamplerKind::Independent) {
    throw InvalidInput(setting("stats_channels") +
                       ": the parts were rendered from one sequence, which keeps no estimate of "
                       "the error: render them with " +
                       setting("stats_channels"));
  }
  if (!sampler.kind) {
    throw InvalidInput(setting("stats_channels") + ": the parts' sampler: " + sampler.unknown);
  }
  return statistics_channels(whole);
}

// The merged render as the denoiser reads it: its halves need the parts' two replicates.
void check_for_denoising(const RenderResult& whole, const RecordedSampler& sampler,
                         std::int64_t replicates) {
  if (replicates != kReplicates || !whole.sums.keeps(SumGroup::Odd) ||
      !whole.sums.keeps(SumGroup::FirstHit)) {
    throw InvalidInput(setting("denoise") +
                       ": the parts keep no independent halves or first hits to denoise with: "
                       "render them with " +
                       setting("denoise"));
  }
  if (!sampler.kind) {
    throw InvalidInput(setting("denoise") + ": the parts' sampler: " + sampler.unknown);
  }
}

MergedImage merge_parts(const std::vector<std::string>& paths, const MergeRequest& request) {
  PartMerge merge(request.reading);
  if (request.reading) request.reading->begin(paths.size() * PartMerge::kPartWork);
  for (const std::string& path : paths) merge.add(path);
  MergedRender merged = std::move(merge).finish();
  MergedImage image;
  image.metadata = merged.metadata;
  image.passes = merged.passes;
  image.samples = merged.samples;
  image.parts = paths.size();
  const std::string without_spreads = merged.without_spreads;
  const auto [sampler_name, replicates] = recorded_sampling(merged);
  const RecordedSampler sampler = parse_recorded_sampler(sampler_name);
  // One render's result of the merged sums, moved, not copied: every channel is made from it.
  RenderResult whole =
      merged_result(std::move(merged), sampler.kind.value_or(SamplerKind::Independent),
                    replicates > 1 ? kReplicates : 1);
  // The replicate ratios of these sums, where the estimate made them.
  whole.replicate_ratios = record_error_estimate(whole, sampler, image.metadata);
  image.estimated_error = whole.estimated_image_error, image.error_estimate = whole.error_estimate;
  if (request.statistics)
    image.channels = merged_statistics(whole, without_spreads, sampler, replicates);
  image.passes_kept = image.passes.any() && request.extra_channels;
  if (image.passes_kept) {
    for (ExtraChannel& c : pass_channels(whole, image.passes))
      image.channels.push_back(std::move(c));
  }
  image.placement = recorded_placement(image.metadata, "part " + quote_value(paths.front()),
                                       whole.film.width(), whole.film.height());
  if (!image.passes_kept) {
    std::erase_if(image.metadata,
                  [](const auto& entry) { return entry.first == metadata_key::kPasses; });
  }
  if (request.denoise) {
    check_for_denoising(whole, sampler, replicates);
    const DenoiseInput input = denoise_input(whole);
    // Every channel made of the sums is made by now: their memory (268 bytes a pixel, more than
    // the denoiser's working set) goes back before the denoiser takes its own.
    whole.sums = PixelSums();
    whole.pixel_samples = {}, whole.pixel_rays = {}, whole.replicate_ratios.reset();
    DenoisedOutput denoised =
        denoised_output(denoise(input, DenoiseControl{request.cancelled, request.denoising}),
                        request.extra_channels, image.metadata);
    image.channels.insert(image.channels.begin(),
                          std::make_move_iterator(denoised.channels.begin()),
                          std::make_move_iterator(denoised.channels.end()));
    image.denoised = denoised.figures;
    whole.film = std::move(denoised.image);
  }
  image.film = std::move(whole.film);
  return image;
}

}  // namespace

MergedImage merge_part_files(const std::vector<std::string>& paths, const MergeRequest& request) {
  check_thread_count(request.threads);
  return with_threads(request.threads, [&] { return merge_parts(paths, request); });
}

MergedImage merge_to_file(const std::vector<std::string>& paths, const std::string& output,
                          MergeRequest request) {
  check_thread_count(request.threads);
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
