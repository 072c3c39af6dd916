#pragma once
// A render as a user asks for it: a scene and what to change about it. The command line and
// the C++ API both go through resolve(), so one request has one meaning: one set of defaults,
// one aspect rule and the same checks, and the same image from either.

#include <cstdint>
#include <optional>

#include "core/geometry/vec3.h"
#include "core/render/render_settings.h"
#include "core/scene/scene.h"
#include "materials/fresnel.h"

namespace rtiow {

// The camera of the scene, with whatever of it is given replaced.
struct CameraOverrides {
  std::optional<Vec3d> lookfrom, lookat, vup;
  std::optional<double> vfov_degrees, aperture, focus_distance;
};

struct RenderRequest {
  // Empty: the scene's. With only one side given, the other follows the scene's aspect ratio.
  std::optional<int> width, height;
  std::optional<PixelRegion> crop;  // of the width x height image (RenderSettings::crop)
  // As --spp: with an error target the most a pixel takes (empty: kDefaultErrorDrivenMaxSpp),
  // with `adaptive` a budget of that many uniform samples (empty: the time limit's, or the
  // scene's count), otherwise every pixel's count (empty: as the time limit allows, or the
  // scene's count). resolve() turns it into a typed SampleBudget.
  std::optional<int> spp;
  std::optional<int> max_depth;  // empty: the scene's
  CameraOverrides camera;
  std::optional<FresnelModel> fresnel;  // empty: as each glass says
  // The rest as RenderSettings says, with its defaults.
  SamplerKind sampler = RenderSettings{}.sampler;
  AccelKind accel = RenderSettings{}.accel;
  std::uint64_t seed = RenderSettings{}.seed;
  int threads = RenderSettings{}.threads;
  double time_limit_seconds = RenderSettings{}.time_limit_seconds;
  // The adaptive modes, at most one (0 and false: off), and their minimum per pixel.
  double target_error = 0.0;          // --target-error: each pixel's relative standard error
  double image_error = 0.0;           // --image-error: the image's relative RMS error
  bool image_error_denoised = false;  // ... of the denoised image (--denoise)
  bool adaptive = false;              // --adaptive: spend the budget where the variance is
  // --stats-channels: keep what an estimate of each pixel's error needs (RenderSettings).
  bool estimate_error = false;
  bool russian_roulette = RenderSettings{}.russian_roulette;  // --roulette
  FirstHitPasses passes;  // --passes: albedo, normal, depth beside the image (.exr)
  // --min-spp: what each pixel takes before an adaptive mode may stop it (empty:
  // kDefaultLeastSamples); refused without one, where it would mean nothing.
  std::optional<int> min_samples;
};

// The scene with the request's changes, and the settings that render it.
struct ResolvedRender {
  Scene scene;
  RenderSettings settings;
};

// Applies the request to the scene and checks the settings (throws InvalidInput naming what is
// wrong); render(result.scene, result.settings), which checks the scene's camera against
// them, renders the requested image.
ResolvedRender resolve(Scene scene, const RenderRequest& request);

}  // namespace rtiow
