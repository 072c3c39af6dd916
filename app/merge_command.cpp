#include "app/merge_command.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/io/error.h"
#include "core/io/image_output.h"
#include "core/io/output_path.h"
#include "core/render/render_part.h"

namespace rtiow {
namespace {

struct MergeOptions {
  std::vector<std::string> parts;
  std::string output;
  bool quiet = false;
};

int run_merge(const MergeOptions& o) {
  namespace fs = std::filesystem;
  check_image_output(o.output, o.parts);
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
  cmd->add_option("parts", options->parts, "Part files (.exr)")->required();
  cmd->add_option("-o,--output", options->output,
                  "The merged image (" + image_extensions() + "); not one of the parts")
      ->required();
  cmd->add_flag("-q,--quiet", options->quiet, "No summary on stderr");
  return [options, cmd] { return cmd->parsed() ? run_merge(*options) : -1; };
}

}  // namespace rtiow
