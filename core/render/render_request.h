#pragma once
// A render as a user asks for it: a scene and what to change about it. The command line and
// the C++ API both go through resolve(), so one request has one meaning: one set of defaults,
// one aspect rule and the same checks, and the same image from either.

#include <cstdint>
#include <optional>

#include "core/geometry/vec3.h"
#include "core/render/render.h"
#include "core/scene/scene.h"
#include "materials/fresnel.h"

namespace rtiow {

// The camera of the scene, with whatever of it is given replaced.
struct CameraOverrides {
  std::optional<Vec3d> lookfrom, lookat, vup;
  std::optional<double> vfov_degrees, aperture, focus_distance;
};

// The most samples a pixel takes under an error target when no --spp caps it.
inline constexpr int kDefaultErrorDrivenMaxSpp = 8192;

struct RenderRequest {
  // Empty: the scene's. With only one side given, the other follows the scene's aspect ratio.
  std::optional<int> width, height;
  // Empty: the scene's count; with an error target, at most kDefaultErrorDrivenMaxSpp per
  // pixel; with only a time limit, as many as the time allows.
  std::optional<int> samples_per_pixel;
  std::optional<int> max_depth;  // empty: the scene's
  CameraOverrides camera;
  std::optional<FresnelModel> fresnel;  // empty: as each glass says
  // The rest as RenderSettings says, with its defaults.
  SamplerKind sampler = RenderSettings{}.sampler;
  AccelKind accel = RenderSettings{}.accel;
  std::uint64_t seed = RenderSettings{}.seed;
  int threads = RenderSettings{}.threads;
  double time_limit_seconds = RenderSettings{}.time_limit_seconds;
  double target_error = RenderSettings{}.target_error;
  double image_error = RenderSettings{}.image_error;
  bool adaptive = RenderSettings{}.adaptive;
  int min_samples = RenderSettings{}.min_samples;
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
