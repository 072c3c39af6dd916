#include "app/merge_command.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/io/image_output.h"
#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/render/render_metadata.h"
#include "core/render/render_part.h"
#include "core/render/render_statistics.h"
#include "core/sampling/sampler.h"

namespace rtiow {
namespace {

struct MergeOptions {
  std::vector<std::string> parts;
  std::string output;
  bool stats_channels = false;
  bool quiet = false;
};

// The spp and variance channels of the merged render, as one render's --stats-channels.
std::vector<ExtraChannel> merged_statistics(const MergedRender& merged,
                                            const std::vector<RenderPart>& parts) {
  if (!merged.sums.keeps(SumGroup::Odd)) {
    for (const RenderPart& p : parts) {
      if (!p.sums.keeps(SumGroup::Odd)) {
        throw InvalidInput("--stats-channels: part file " + quote_value(p.path, kWholePath) +
                           " holds no spreads (an older rtiow wrote it): render it again");
      }
    }
  }
  std::string sampler;
  std::int64_t replicates = kReplicates;  // an older rtiow's parts always had two
  for (const auto& [key, value] : merged.metadata) {
    if (const auto* text = std::get_if<std::string>(&value); key == metadata_key::kSampler && text)
      sampler = *text;
    if (const auto* n = std::get_if<std::int64_t>(&value); key == metadata_key::kReplicates && n)
      replicates = *n;
  }
  if (replicates != kReplicates && sampler != to_string(SamplerKind::Independent)) {
    throw InvalidInput(
        "--stats-channels: the parts were rendered from one sequence, which keeps no estimate of "
        "the error: render them with --stats-channels");
  }
  try {
    return statistics_channels(merged_result(merged, parse_sampler(sampler), int(replicates)));
  } catch (const InvalidInput& e) {
    throw InvalidInput("--stats-channels: the parts' sampler: " + std::string(e.what()));
  }
}

int run_merge(const MergeOptions& o) {
  namespace fs = std::filesystem;
  check_image_output(o.output, o.parts);
  const ImageFormat* format = image_format(o.output);
  if (o.stats_channels && format && !format->extra_channels) {
    throw InvalidInput("--stats-channels: output " + quote_value(o.output) +
                       " must be .exr to hold the spp and variance channels");
  }
  const OutputClaim claim(o.output);  // before the parts are read: a second writer is refused now
  std::vector<RenderPart> parts;
  for (const std::string& path : o.parts) parts.push_back(read_part(path));
  const MergedRender merged = merge_parts(parts);
  std::vector<ExtraChannel> channels =
      o.stats_channels ? merged_statistics(merged, parts) : std::vector<ExtraChannel>{};
  // The passes the parts were rendered with, where the output holds them.
  const bool passes = merged.passes.any() && format && format->extra_channels;
  if (passes) {
    const RenderResult whole = merged_result(merged, SamplerKind::Independent, kReplicates);
    for (ExtraChannel& c : pass_channels(whole, merged.passes)) channels.push_back(std::move(c));
  } else if (merged.passes.any()) {
    std::fprintf(stderr,
                 "rtiow: warning: the parts hold the passes %s, which %s cannot: merge to .exr "
                 "to keep them\n",
                 to_string(merged.passes).c_str(), quote_value(o.output).c_str());
  }
  Metadata metadata = merged.metadata;
  if (!passes) {
    std::erase_if(metadata, [](const auto& entry) { return entry.first == metadata_key::kPasses; });
  }
  write_image(o.output, merged.film, metadata, channels,
              recorded_placement(merged.metadata, "part " + quote_value(o.parts.front()),
                                 merged.film.width(), merged.film.height()));
  if (!o.quiet) {
    std::fprintf(
        stderr, "merged %zu parts: %dx%d, %llu spp%s -> %s\n", parts.size(), merged.film.width(),
        merged.film.height(), static_cast<unsigned long long>(merged.samples),
        passes ? (", passes " + to_string(merged.passes)).c_str() : "", one_line(o.output).c_str());
  }
  return 0;
}

}  // namespace

std::function<int()> add_merge_command(CLI::App& app) {
  auto options = std::make_shared<MergeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "merge",
      "Add part files (rtiow render --sample-range/--part) into the image one render "
      "would have produced; checks they belong together, overlap nowhere and miss nothing");
  cmd->add_option("parts", options->parts, "Part files (.exr)")->required();
  cmd->add_option("-o,--output", options->output,
                  "The merged image (" + image_extensions() + "); not one of the parts")
      ->required();
  cmd->add_flag("--stats-channels", options->stats_channels,
                "Add per-pixel channels to an .exr output: spp and the variance of the pixel's "
                "mean (variance.R/G/B), the same as one render's --stats-channels");
  cmd->add_flag("-q,--quiet", options->quiet, "No summary on stderr");
  return [options, cmd] { return cmd->parsed() ? run_merge(*options) : -1; };
}

}  // namespace rtiow
