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
namespace {

struct MergeOptions {
  std::vector<std::string> parts;
  std::string output;
  bool stats_channels = false;
  bool quiet = false;
};

int run_merge(const MergeOptions& o) {
  check_image_output(o.output, o.parts);
  const ImageFormat* format = image_format(o.output);
  if (o.stats_channels && format && !format->extra_channels) {
    throw InvalidInput("--stats-channels: output " + quote_value(o.output) +
                       " must be .exr to hold the spp and variance channels");
  }
  const OutputClaim claim(o.output);  // before the parts are read: a second writer is refused now
  const MergedImage merged =
      merge_part_files(o.parts, {o.stats_channels, format && format->extra_channels});
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
