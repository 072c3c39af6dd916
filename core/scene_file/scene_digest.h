#pragma once
// A digest of a scene: equal for equal scenes (a scene and the scene its file reads back as),
// different for any change to a sphere, a material, the camera, the sky or the image
// settings. A checkpoint and a render's parts carry it, so they continue or merge only the
// scene they were made from.

#include <string>

#include "core/scene/scene.h"

namespace rtiow {

// 16 hexadecimal digits.
std::string scene_digest(const Scene& scene);

}  // namespace rtiow
