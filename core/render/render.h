#pragma once
// One render: a scene, settings and a seed in, a film out. The result is a pure function
// of (scene, settings without `threads`, seed): identical for any thread count and for
// either accelerator.

#include "core/render/render_settings.h"
#include "core/scene/scene.h"

namespace rtiow {

// Everything a render checks before any work: the settings, the scene, and that the camera
// rays of this image size are traceable. Throws InvalidInput.
void validate(const Scene& scene, const RenderSettings& settings);

struct Checkpointing;  // core/render/render_state.h
struct RenderState;

// The state a render ended in, moved out of its result (its sums, counts and targets), for a
// caller that keeps it after the render (in a checkpoint, when the image could not be written),
// and moved back by restore_state. A copy needed the render's memory over again: a 4000x2667
// render whose image write ran out of memory under `ulimit -v` could not keep its state.
RenderState take_state(RenderResult& result);
void restore_state(RenderState&& state, RenderResult& result);

// Validates the scene's camera and the settings (throwing InvalidInput before any work),
// builds the accelerator and renders in passes: each pass adds a few samples to every
// pixel, and the pixel sums continue across passes in sample order, so the image does not
// depend on how samples were grouped into passes. With `checkpointing`, the render starts
// from a saved state and saves its own as it goes: continued, it gives the same bits.
//
// What `settings` leave to the scene (a side or the count of 0, the depth) is taken from its image
// settings first (with_scene_image).
RenderResult render(const Scene& scene, const RenderSettings& settings,
                    RenderProgress* progress = nullptr,
                    const Checkpointing* checkpointing = nullptr);

// `settings` with what they leave to the scene filled in from its ImageSettings: width and
// height 0 (one of them 0: it follows the other and the aspect ratio), a FixedSamples count
// of 0, a max_depth of kSceneDepth. A library render so takes every setting a scene file
// makes, as `rtiow render FILE` does.
RenderSettings with_scene_image(const Scene& scene, RenderSettings settings);

// Starts oneTBB now rather than at the render's first pass. oneTBB dlopens its allocator on
// first use, and a dlopen waits for any other under way: a program that loads a library on
// another thread during the render (the image backend) calls this first, or the render
// waits for that whole load.
void start_parallel_runtime();

}  // namespace rtiow
