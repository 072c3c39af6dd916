#pragma once
// rtiow as a library, in one include: build a Scene (or load one), render it with
// RenderSettings, write the film. What the `rtiow` command line does, without it.

#include "core/io/image_output.h"       // write_image
#include "core/render/render.h"         // RenderSettings, render, validate
#include "core/scene/builtin_scenes.h"  // make_builtin_scene
#include "core/scene/scene.h"           // Scene, CameraSettings, Background
#include "core/scene/scene_file.h"      // load_scene_file, scene_to_json
#include "materials/material.h"         // Lambertian, Metal, Dielectric
