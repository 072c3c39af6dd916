#include "core/render/render_request.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <variant>

#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/limits/setting_name.h"

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

// What --spp means is decided here, once: a count, a budget or a cap, by the mode beside it.
SampleBudget budget_asked(const RenderRequest& r, const ImageSettings& image) {
  const auto error_option = [](double error, const char* what, const char* name) {
    if (!(error >= 0.0) || !std::isfinite(error)) {
      throw InvalidInput(std::string(what) + " must be a finite number >= 0 (0: off)");
    }
    // A relative error of 1 is the size of the values themselves: 2 is a slip for 2%, and the
    // render would stop at the minimum while its summary claimed the target met.
    if (error >= 1.0) {
      char shown[32];
      const std::string value(shown, std::to_chars(shown, shown + sizeof shown, error).ptr);
      throw InvalidInput(setting(name, value) +
                         " is a relative error of 100% or more: give a fraction below 1 (0.02 "
                         "for 2%)");
    }
    return error > 0.0;
  };
  const bool by_pixel = error_option(r.target_error, "target error", "target_error");
  const bool by_image = error_option(r.image_error, "image error", "image_error");
  if (int(by_pixel) + int(by_image) + int(r.adaptive) > 1) {
    throw InvalidInput("choose one adaptive mode: " + setting("target_error") + " (per pixel), " +
                       setting("image_error") + " or " + setting("adaptive") + " (a budget)");
  }
  if (r.min_samples && !by_pixel && !by_image && !r.adaptive) {
    throw InvalidInput(setting("min_spp", std::to_string(*r.min_samples)) +
                       " applies to adaptive sampling (" + setting("target_error") + ", " +
                       setting("image_error") + " or " + setting("adaptive") +
                       "); a uniform render gives every pixel " + setting("spp"));
  }
  const int least = r.min_samples.value_or(kDefaultLeastSamples);
  if (least < 2) {
    throw InvalidInput(setting("min_spp") + " must be >= 2 (a variance needs two), got " +
                       std::to_string(least));
  }
  const int cap = r.spp.value_or(kDefaultErrorDrivenMaxSpp);
  if (by_pixel) return PixelErrorTarget{r.target_error, cap, least};
  if (by_image) return ImageErrorTarget{r.image_error, cap, least, r.image_error_denoised};
  const bool timed = r.time_limit_seconds > 0.0;
  if (r.adaptive) {
    // With only a time limit, the time is the budget; with neither, the scene's count.
    const std::optional<int> spp = r.spp   ? r.spp
                                   : timed ? std::nullopt
                                           : std::optional<int>(image.samples_per_pixel);
    // A budget no larger than the minimum leaves nothing to allocate: the render would be
    // uniform while its metadata says adaptive.
    if (spp && *spp > 0 && *spp <= least) {
      throw InvalidInput(setting("adaptive") + ": a budget of " + std::to_string(*spp) +
                         " spp leaves nothing to allocate after every pixel's minimum of " +
                         std::to_string(least) + " (" + setting("min_spp") + "); give " +
                         setting("spp") + " above it, or leave out " + setting("adaptive") +
                         " for a uniform render");
    }
    return AdaptiveBudget{spp, least};
  }
  if (r.spp) return FixedSamples{*r.spp};
  if (timed) return UntilTimeLimit{};
  return FixedSamples{image.samples_per_pixel};
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
        derived_side(s.height, width_for_height(s.height, image.aspect_ratio), "width", "height");
  } else {
    s.width = r.width.value_or(image.width);
    s.height =
        derived_side(s.width, height_for_width(s.width, image.aspect_ratio), "height", "width");
  }
  s.crop = r.crop;
  s.samples = budget_asked(r, image);
  s.max_depth = r.max_depth.value_or(image.max_depth);
  s.seed = r.seed;
  s.threads = r.threads;
  s.time_limit_seconds = r.time_limit_seconds;
  s.accel = r.accel;
  s.sampler = r.sampler;
  s.estimate_error = r.estimate_error;
  s.russian_roulette = r.russian_roulette;
  s.passes = r.passes;
  validate(s);
  return {std::move(scene), s};
}

}  // namespace rtiow
