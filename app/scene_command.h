#pragma once
// `rtiow scene NAME`: writes a built-in scene as a scene file (JSON), to stdout or a file.
// Rendering that file gives the same image as rendering the built-in scene.

#include <CLI/CLI.hpp>

#include <functional>

namespace rtiow {

std::function<int()> add_scene_command(CLI::App& app);

}  // namespace rtiow
