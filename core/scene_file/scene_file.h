#pragma once
// Scene files: JSON that models exactly what the renderer models. The format, version 1:
//
//   {
//     "version": 1,
//     "name": "my scene",                       optional, default: the file's stem
//     "scene_seed": 7,                          optional provenance of a generated layout
//     "camera": {"lookfrom": [13, 2, 3], "lookat": [0, 0, 0], "vup": [0, 1, 0],
//                "vfov": 20, "aperture": 0.1, "focus_distance": 10},
//     "image": {"width": 1200, "aspect_ratio": 1.5, "spp": 500, "depth": 50},
//     "background": {"horizon": [1, 1, 1], "zenith": [0.5, 0.7, 1]},
//     "materials": {"ground": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]},
//                   "chrome": {"type": "metal", "albedo": [0.7, 0.6, 0.5], "fuzz": 0},
//                   "glass": {"type": "dielectric", "ior": 1.5}},
//     "spheres": [{"center": [0, -1000, 0], "radius": 1000, "material": "ground"}]
//   }
//
// Unknown fields are errors (a typo must not silently change a render). Every error names
// the file and the place: "line L, column C" for syntax, a JSON pointer for content.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "core/limits/error.h"
#include "core/scene/scene.h"

namespace rtiow {

// Parses scene JSON; `source` names it in errors. Throws InvalidInput.
Scene parse_scene(const std::string& text, const std::string& source);

// Reads and parses a scene file, or standard input for "-". Throws InvalidInput (including
// for unreadable files).
Scene load_scene_file(const std::string& path);

// A scene file this big or bigger is parsed in runs (read_scene_in_runs), on every core there
// is, read kSplitWindowBytes at a time, each window's members in one run per container. (Also
// on one core: its members are read straight into records, without the JSON values the
// one-piece parse builds for its messages.)
inline constexpr std::uint64_t kSplitFileBytes = std::uint64_t(4) << 20;
inline constexpr std::size_t kSplitWindowBytes = std::size_t(4) << 20;
inline constexpr std::size_t kSplitRunBytes = kSplitWindowBytes;

// Scene JSON from `source` (named `name` in errors) parsed in runs of members on every core of
// the calling thread's arena (core/scene_file/json_split.h, run_records.h), to the same scene as
// parse_scene; or
// nothing when that fails for any reason, including every error in the text (parse it in one
// piece then, for the error's message).
std::optional<Scene> read_scene_in_runs(
    const std::function<std::size_t(char*, std::size_t)>& source, const std::string& name,
    std::size_t run_bytes, std::size_t window_bytes);

// The scene as version-1 JSON. Floats are written in their shortest form that reads back
// to the same bits, so a written scene renders the identical image.
std::string scene_to_json(const Scene& scene);

// The scene's settings (all of it but its materials and spheres): the lines that begin that
// text, up to its materials.
std::string scene_settings_json(const Scene& scene);

// The same text, handed to `sink` piece by piece in order (for a digest of a large scene
// without holding its text); formatted on every core of the calling thread's arena.
void write_scene_json(const Scene& scene, const std::function<void(std::string_view)>& sink);

}  // namespace rtiow
