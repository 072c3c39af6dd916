#include "core/camera.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "core/error.h"
#include "core/sampling.h"

namespace rtiow {
namespace {

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

void require(bool ok, const std::string& message) {
  if (!ok) throw InvalidInput("camera: " + message);
}

}  // namespace

void validate(const CameraSettings& s) {
  require(is_finite(s.lookfrom), "lookfrom is not finite");
  require(is_finite(s.lookat), "lookat is not finite");
  require(is_finite(s.vup), "vup is not finite");
  const Vec3d view = s.lookat - s.lookfrom;
  require(length_squared(view) > 0.0, "lookfrom equals lookat, so there is no view direction");
  // Relative test: vup must not be (nearly) parallel to the view direction.
  const double vup_len = length(s.vup);
  require(vup_len > 0.0, "vup is the zero vector");
  require(length(cross(normalize(view), s.vup / vup_len)) > 1e-9,
          "vup is parallel to the view direction (lookat - lookfrom)");
  require(std::isfinite(s.vfov_degrees) && s.vfov_degrees > 0.0 && s.vfov_degrees < 180.0,
          "vfov must lie strictly between 0 and 180 degrees, got " + number(s.vfov_degrees));
  require(std::isfinite(s.aperture) && s.aperture >= 0.0,
          "aperture must be finite and >= 0, got " + number(s.aperture));
  require(std::isfinite(s.focus_distance) && s.focus_distance > 0.0,
          "focus distance must be finite and > 0, got " + number(s.focus_distance));
}

Camera::Camera(const CameraSettings& s, int image_width, int image_height) {
  validate(s);
  const double aspect = double(image_width) / double(image_height);
  const double h = std::tan(s.vfov_degrees * std::numbers::pi / 360.0);
  const double viewport_height = 2.0 * h;
  const double viewport_width = aspect * viewport_height;

  const Vec3d w = normalize(s.lookfrom - s.lookat);
  const Vec3d u = normalize(cross(s.vup, w));
  const Vec3d v = cross(w, u);

  const Vec3d horizontal = s.focus_distance * viewport_width * u;
  const Vec3d vertical = -s.focus_distance * viewport_height * v;  // film t grows downwards
  const Vec3d upper_left = s.lookfrom - 0.5 * horizontal - 0.5 * vertical - s.focus_distance * w;

  origin_ = Vec3(s.lookfrom);
  // Store the corner relative to the origin: rays are built as direction vectors, so a
  // camera far from the world origin does not lose the film's precision.
  upper_left_ = Vec3(upper_left - s.lookfrom);
  horizontal_ = Vec3(horizontal);
  vertical_ = Vec3(vertical);
  u_ = Vec3(u);
  v_ = Vec3(v);
  lens_radius_ = float(0.5 * s.aperture);
}

Ray Camera::generate_ray(float s, float t, float lens_u, float lens_v) const {
  const Vec3 film = upper_left_ + s * horizontal_ + t * vertical_;
  if (lens_radius_ == 0.0f) return Ray{origin_, film};
  const Vec3 disk = lens_radius_ * sample_in_unit_disk(lens_u, lens_v);
  const Vec3 offset = disk.x * u_ + disk.y * v_;
  return Ray{origin_ + offset, film - offset};
}

}  // namespace rtiow
