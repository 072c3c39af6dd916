#pragma once
// The scenes of Ray Tracing in One Weekend (v3.2.3), by name.

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace rtiow {

struct BuiltinScene {
  std::string name;
  std::string summary;
};

const std::vector<BuiltinScene>& builtin_scenes();

// Whether `name` is a built-in scene (spheres:N included, for any N in range).
bool is_builtin_scene_name(const std::string& name);

// The layout seed of a built-in scene when none is given (--scene-seed).
inline constexpr std::uint64_t kDefaultSceneSeed = 1;

// Builds the named scene. `scene_seed` chooses the random layout of the cover scene and
// of the `spheres:N` family; the others ignore it. Throws InvalidInput for unknown names.
Scene make_builtin_scene(const std::string& name, std::uint64_t scene_seed);

}  // namespace rtiow
