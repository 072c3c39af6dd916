#pragma once
// rtiow as a library, in one include: build a Scene (or load one), resolve a RenderRequest
// against it (or fill RenderSettings yourself), render, write the film. The same request gives
// the image `rtiow render` gives for the same options.

#include "core/compare/image_comparison.h"  // compare_image_files: rtiow diff
#include "core/io/image_channels.h"         // read_image_channels: an image's channels
#include "core/io/image_output.h"           // write_image
#include "core/limits/setting_name.h"       // spell_settings_as: how messages name settings
#include "core/render/checkpoint_file.h"    // write_checkpoint, read_checkpoint: --resume
#include "core/render/part_merge.h"         // merge_part_files: rtiow merge
#include "core/render/recorded_request.h"   // read_recorded_request, overlay_recorded: --like
#include "core/render/render.h"             // RenderSettings, render, validate
#include "core/render/render_metadata.h"    // render_metadata: what --like reads back
#include "core/render/render_part.h"        // make_part, write_part, PartMerge
#include "core/render/render_request.h"     // RenderRequest, resolve: what the command line does
#include "core/scene/builtin_scenes.h"      // make_builtin_scene
#include "core/scene/scene.h"               // Scene, CameraSettings, Background
#include "core/scene_file/scene_file.h"     // load_scene_file, scene_to_json
#include "core/session/render_session.h"    // RenderSession: what rtiow render runs
#include "core/version.h"                   // version
#include "materials/material.h"             // Lambertian, Metal, Dielectric
