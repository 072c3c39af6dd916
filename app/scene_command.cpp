#include "app/scene_command.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "core/atomic_file.h"
#include "core/builtin_scenes.h"
#include "core/error.h"
#include "core/scene_file.h"

namespace rtiow {
namespace {

struct SceneOptions {
  std::string name;
  std::uint64_t scene_seed = 1;
  std::string output;
};

int run_scene(const SceneOptions& o) {
  const std::string text = scene_to_json(make_builtin_scene(o.name, o.scene_seed));
  if (o.output.empty() || o.output == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    return std::fflush(stdout) == 0 ? 0 : 1;
  }
  const std::filesystem::path parent = std::filesystem::path(o.output).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent)) {
    throw InvalidInput("output '" + o.output + "': directory '" + parent.string() +
                       "' does not exist");
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
      ->capture_default_str();
  cmd->add_option("-o,--output", options->output, "Write here instead of to stdout");
  return [options, cmd] { return cmd->parsed() ? run_scene(*options) : -1; };
}

}  // namespace rtiow
