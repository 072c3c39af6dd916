#pragma once
// `rtiow scene NAME`: writes a built-in scene as a scene file (JSON), to stdout or a file.
// Rendering that file gives the same image as rendering the built-in scene.

#include <cstdint>
#include <string>

#include "core/scene/builtin_scenes.h"

namespace rtiow {

struct SceneOptions {
  std::string name;
  std::uint64_t scene_seed = kDefaultSceneSeed;
  std::string output;
  bool output_given = false;  // -o was given (an empty path is refused, not stdout)
};

int run_scene(const SceneOptions& o);

}  // namespace rtiow
