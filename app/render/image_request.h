#pragma once
// `rtiow render --like IMAGE`: the request an image's provenance records (its rtiow:* keys,
// docs/usage.md "Output"), as the render command's own options, so the image can be rendered
// again, or rendered again with some of it changed.

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/render/render_request.h"

namespace rtiow {

struct ImageRequest {
  // Options in the render command's spelling ("--spp", {"64"}), grouped: an option the user
  // gives replaces its whole group (a scene, the sampling, one camera setting, ...).
  struct Option {
    std::string group;
    std::string name;  // "scene_file" for the positional scene file
    std::vector<std::string> values;
    std::string unrepeatable;  // else: why no render repeats this part (no name, no values)
  };
  std::vector<Option> options;
  // What the recorded scene must digest to, once the recorded camera and glass model are
  // applied: a scene file edited since gives another digest.
  std::string scene_digest;
  CameraOverrides camera;
  std::optional<FresnelModel> fresnel;
  std::string scene_file;  // the file the scene was read from, if any
  std::string version;     // the rtiow that rendered it
};

// Reads `path`'s header. Throws InvalidInput naming the image and what is missing where it
// holds no rtiow request (a format without text, an older rtiow, a part file) or one that no
// render repeats (an adaptive render stopped by a signal or a clock).
ImageRequest read_image_request(const std::string& path);

// Gives the parsed `render` command the image's options, but for each group of which the user
// gave an option. Returns whether the user chose the scene (then no digest is checked).
bool apply_image_request(const ImageRequest& request, CLI::App& render);

// Throws InvalidInput where `scene`, with the image's camera and glass model, is not the scene
// the image was rendered from (a scene file edited since, or another rtiow's built-in scene).
void check_scene_of_image(const ImageRequest& request, const Scene& scene,
                          const std::string& image);

}  // namespace rtiow
