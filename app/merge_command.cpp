#include "app/merge_command.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image_output.h"
#include "core/render_part.h"

namespace rtiow {
namespace {

struct MergeOptions {
  std::vector<std::string> parts;
  std::string output;
  bool quiet = false;
};

int run_merge(const MergeOptions& o) {
  namespace fs = std::filesystem;
  const fs::path parent = fs::path(o.output).parent_path();
  if (!parent.empty() && !fs::is_directory(parent)) {
    throw InvalidInput("output '" + o.output + "': directory '" + parent.string() +
                       "' does not exist");
  }
  if (!is_writable_image_path(o.output)) {
    throw InvalidInput("output '" + o.output + "': unknown image format");
  }
  std::vector<RenderPart> parts;
  for (const std::string& path : o.parts) parts.push_back(read_part(path));
  const MergedRender merged = merge_parts(parts);
  write_image(o.output, merged.film, merged.metadata);
  if (!o.quiet) {
    std::fprintf(stderr, "merged %zu parts: %dx%d, %llu spp -> %s\n", parts.size(),
                 merged.film.width(), merged.film.height(),
                 static_cast<unsigned long long>(merged.samples), fs::absolute(o.output).c_str());
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
  cmd->add_option("parts", options->parts, "Part files (.exr)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", options->output, "The merged image (any format)")->required();
  cmd->add_flag("-q,--quiet", options->quiet, "No summary on stderr");
  return [options, cmd] { return cmd->parsed() ? run_merge(*options) : -1; };
}

}  // namespace rtiow
