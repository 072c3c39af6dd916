#include "app/scene_command.h"

#include "app/cli_checks.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/io/atomic_file.h"
#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/scene/builtin_scenes.h"
#include "core/scene_file/scene_file.h"

namespace rtiow {
namespace {

struct SceneOptions {
  std::string name;
  std::uint64_t scene_seed = kDefaultSceneSeed;
  std::string output;
};

int run_scene(const SceneOptions& o, bool output_given) {
  if (output_given && o.output.empty()) throw InvalidInput("-o/--output: the path is empty");
  const bool to_stdout = o.output.empty() || o.output == "-";
  if (!to_stdout) check_output_path(o.output, {});
  // `rtiow scene cover -o c.png` would write JSON under an image's name.
  if (!to_stdout && image_format(o.output) != nullptr) {
    throw InvalidInput("-o " + quote_value(o.output) +
                       ": a scene is JSON, not an image; name it .json (an image of it: rtiow "
                       "render --scene " +
                       o.name + " -o " + o.output + ")");
  }
  std::optional<OutputClaim> claim;  // held from before the scene is made
  if (!to_stdout) claim.emplace(o.output);
  const std::string text = scene_to_json(make_builtin_scene(o.name, o.scene_seed));
  if (to_stdout) {
    std::fwrite(text.data(), 1, text.size(), stdout);
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
      throw std::runtime_error(std::string("cannot write to standard output: ") +
                               std::strerror(errno));
    }
    return 0;
  }
  write_text_atomically(o.output, text);
  return 0;
}

}  // namespace

std::function<int()> add_scene_command(CLI::App& app) {
  auto options = std::make_shared<SceneOptions>();
  CLI::App* cmd = app.add_subcommand(
      "scene", "Write a built-in scene as a scene file (JSON) that renders the same image");
  cmd->add_option("name", options->name, "Built-in scene (see rtiow render --list-scenes)")
      ->required();
  cmd->add_option("--scene-seed", options->scene_seed,
                  "Seed of the random layout of cover and spheres:N")
      ->check(kNotNegative)
      ->capture_default_str();
  CLI::Option* output =
      cmd->add_option("-o,--output", options->output, "Write here instead of to stdout ('-')");
  return [options, cmd, output] {
    return cmd->parsed() ? run_scene(*options, output->count() > 0) : -1;
  };
}

}  // namespace rtiow
