#include "core/render/render_request.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <variant>

#include "core/limits/error.h"
#include "core/limits/input_limits.h"

namespace rtiow {
namespace {

// The side an image takes from the other and the aspect ratio: checked, never clamped.
int derived_side(int given, double derived, const char* side, const char* option) {
  // A given side out of range: validate() refuses it by name; the derived one stays valid, so
  // the message is about the side the user gave.
  if (given < 1 || given > limits::kMaxImageSide) return 1;
  if (!(derived >= 1.0 && derived <= double(limits::kMaxImageSide))) {
    char text[64];
    std::snprintf(text, sizeof text, "%.6g", derived);
    throw InvalidInput(std::string("the scene's aspect ratio gives a ") + side + " of " + text +
                       " pixels for " + option + " " + std::to_string(given) + " (must be 1 to " +
                       std::to_string(limits::kMaxImageSide) + "): give both sides");
  }
  return int(derived);
}

void apply_camera(const CameraOverrides& o, CameraSettings& cam) {
  if (o.lookfrom) cam.lookfrom = *o.lookfrom;
  if (o.lookat) cam.lookat = *o.lookat;
  if (o.vup) cam.vup = *o.vup;
  if (o.vfov_degrees) cam.vfov_degrees = *o.vfov_degrees;
  if (o.aperture) cam.aperture = *o.aperture;
  if (o.focus_distance) cam.focus_distance = *o.focus_distance;
}

void apply_fresnel(FresnelModel model, Scene& scene) {
  for (Material& m : scene.materials) {
    if (auto* d = std::get_if<Dielectric>(&m)) d->fresnel = model;
  }
}

int samples_asked(const RenderRequest& r, const ImageSettings& image) {
  if (r.samples_per_pixel) return *r.samples_per_pixel;
  if (r.target_error > 0 || r.image_error > 0) return kDefaultErrorDrivenMaxSpp;
  if (r.time_limit_seconds > 0) return kSamplesUntilTimeLimit;
  return image.samples_per_pixel;
}

}  // namespace

ResolvedRender resolve(Scene scene, const RenderRequest& r) {
  apply_camera(r.camera, scene.camera);
  if (r.fresnel) apply_fresnel(*r.fresnel, scene);

  RenderSettings s;
  const ImageSettings& image = scene.image;
  if (r.width && r.height) {
    s.width = *r.width, s.height = *r.height;
  } else if (r.height) {
    s.height = *r.height;
    s.width =
        derived_side(s.height, width_for_height(s.height, image.aspect_ratio), "width", "--height");
  } else {
    s.width = r.width.value_or(image.width);
    s.height =
        derived_side(s.width, height_for_width(s.width, image.aspect_ratio), "height", "--width");
  }
  s.samples_per_pixel = samples_asked(r, image);
  s.max_depth = r.max_depth.value_or(image.max_depth);
  s.seed = r.seed;
  s.threads = r.threads;
  s.time_limit_seconds = r.time_limit_seconds;
  s.accel = r.accel;
  s.sampler = r.sampler;
  s.target_error = r.target_error;
  s.image_error = r.image_error;
  s.adaptive = r.adaptive;
  s.min_samples = r.min_samples;
  validate(s);
  return {std::move(scene), s};
}

}  // namespace rtiow
