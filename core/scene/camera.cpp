#include "core/scene/camera.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/parallel/instruction_sets.h"
#include "core/sampling/sampling.h"
#include "core/sampling/unit_circle.h"

namespace rtiow {
namespace {

std::string message_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

void require(bool ok, const std::string& message) {
  if (!ok) throw InvalidInput("camera: " + message);
}

// Each component finite and within the range rtiow traces.
void require_bounded(const Vec3d& v, const char* name) {
  for (int i = 0; i < 3; ++i) {
    const double c = v[std::size_t(i)];
    require(std::isfinite(c) && std::abs(c) <= limits::kMaxCoordinate,
            std::string(name) + "[" + std::to_string(i) + "] must be finite and within +-" +
                message_number(limits::kMaxCoordinate) + " (the range rtiow traces), got " +
                message_number(c));
  }
}

}  // namespace

void validate(const CameraSettings& s) {
  require_bounded(s.lookfrom, "lookfrom");
  require_bounded(s.lookat, "lookat");
  require_bounded(s.vup, "vup");
  const Vec3d view = s.lookat - s.lookfrom;
  require(length_squared(view) > 0.0, "lookfrom equals lookat, so there is no view direction");
  // Relative test: vup must not be (nearly) parallel to the view direction.
  const double vup_len = length(s.vup);
  require(vup_len > 0.0, "vup is the zero vector");
  require(length(cross(normalize(view), s.vup / vup_len)) > 1e-9,
          "vup is parallel to the view direction (lookat - lookfrom)");
  require(
      std::isfinite(s.vfov_degrees) && s.vfov_degrees > 0.0 && s.vfov_degrees < 180.0,
      "vfov must lie strictly between 0 and 180 degrees, got " + message_number(s.vfov_degrees));
  require(std::isfinite(s.aperture) && s.aperture >= 0.0 && s.aperture <= limits::kMaxCoordinate,
          "aperture must be from 0 to " + message_number(limits::kMaxCoordinate) + ", got " +
              message_number(s.aperture));
  const double focus = focus_distance_of(s);
  require(std::isfinite(focus) && focus >= kMinFocusDistance && focus <= limits::kMaxCoordinate,
          "focus distance must be from " + message_number(kMinFocusDistance) + " to " +
              message_number(limits::kMaxCoordinate) + ", got " + message_number(focus));
}

double focus_distance_of(const CameraSettings& s) {
  return s.focus_distance ? *s.focus_distance : length(s.lookat - s.lookfrom);
}

void validate(const CameraSettings& s, int image_width, int image_height) {
  validate(s);
  // The film spans focus_distance * tan(vfov / 2) * aspect: a wide view of a wide image
  // far away can still produce rays Embree refuses, so bound the rays themselves.
  const Camera camera(s, image_width, image_height);
  require(camera.max_ray_component() <= limits::kMaxRayComponent,
          "its rays reach " + message_number(camera.max_ray_component()) +
              ", beyond the limit of " + message_number(limits::kMaxRayComponent) +
              " (narrow vfov, focus distance or aspect ratio)");
}

Camera::Camera(const CameraSettings& s, int image_width, int image_height) {
  validate(s);
  if (image_width <= 0 || image_height <= 0) throw InvalidInput("camera: the image has no pixels");
  const double aspect = double(image_width) / double(image_height);
  const double h = std::tan(s.vfov_degrees * std::numbers::pi / 360.0);
  const double viewport_height = 2.0 * h;
  const double viewport_width = aspect * viewport_height;

  const Vec3d w = normalize(s.lookfrom - s.lookat);
  const Vec3d u = normalize(cross(s.vup, w));
  const Vec3d v = cross(w, u);

  const double focus = focus_distance_of(s);
  const Vec3d horizontal = focus * viewport_width * u;
  const Vec3d vertical = -focus * viewport_height * v;  // film t grows downwards
  const Vec3d upper_left = s.lookfrom - 0.5 * horizontal - 0.5 * vertical - focus * w;

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

double Camera::max_ray_component() const {
  double most = 0.0;
  for (int i = 0; i < 3; ++i) {
    const auto axis = std::size_t(i);
    // Film corners and lens offsets bound every ray's direction and origin, per axis.
    const double lens =
        double(lens_radius_) * (std::abs(double(u_[axis])) + std::abs(double(v_[axis])));
    const double direction = std::abs(double(upper_left_[axis])) +
                             std::abs(double(horizontal_[axis])) +
                             std::abs(double(vertical_[axis])) + lens;
    most = std::max({most, direction, std::abs(double(origin_[axis])) + lens});
  }
  return std::isfinite(most) ? most : std::numeric_limits<double>::infinity();
}

Ray Camera::generate_ray(float s, float t, float lens_u, float lens_v) const {
  const Vec3 film = upper_left_ + s * horizontal_ + t * vertical_;
  if (lens_radius_ == 0.0f) return Ray{origin_, film};
  const Vec3 disk = lens_radius_ * sample_in_unit_disk(lens_u, lens_v);
  const Vec3 offset = disk.x * u_ + disk.y * v_;
  return Ray{origin_ + offset, film - offset};
}

namespace {

// A camera's frame, as generate_rays needs it.
struct Frame {
  Vec3 origin, upper_left, horizontal, vertical, u, v;
  float lens_radius;
};

// The lanes' loop, cloned for each instruction set. File-local: a cloned member function
// declared in the header without the attribute is an ODR mismatch to GCC's link-time
// optimiser.
RTIOW_DISPATCHED void lanes_to_rays(const Frame& f, const Camera::Lanes& in, Ray* out) {
  constexpr int kLanes = Camera::kLanes;
  alignas(32) float ox[kLanes], oy[kLanes], oz[kLanes], dx[kLanes], dy[kLanes], dz[kLanes];
  const bool lens = f.lens_radius != 0.0f;
  for (int k = 0; k < kLanes; ++k) {
    const float s = in.s[k], t = in.t[k];
    const float film_x = f.upper_left.x + s * f.horizontal.x + t * f.vertical.x;
    const float film_y = f.upper_left.y + s * f.horizontal.y + t * f.vertical.y;
    const float film_z = f.upper_left.z + s * f.horizontal.z + t * f.vertical.z;
    // sample_in_unit_disk's operations in its order, its branches as selects.
    const float a = 2.0f * in.lens_u[k] - 1.0f, b = 2.0f * in.lens_v[k] - 1.0f;
    const bool centre = a == 0.0f && b == 0.0f;
    const bool along_a = std::abs(a) > std::abs(b);
    // Every operation unconditional and only the values selected: GCC speculates no floating
    // point operation (it might trap), so a conditional one would keep the loop scalar.
    const float radius = along_a ? a : b;
    const float ratio = (along_a ? b : a) / radius;
    const float eighth = 0.125f * ratio;
    const float turns = along_a ? eighth : 0.25f - eighth;
    const CirclePoint angle = circle_point(turns);
    const float disk_cos = radius * angle.cos, disk_sin = radius * angle.sin;
    const float disk_x = f.lens_radius * (centre ? 0.0f : disk_cos);
    const float disk_y = f.lens_radius * (centre ? 0.0f : disk_sin);
    const float offset_x = disk_x * f.u.x + disk_y * f.v.x;
    const float offset_y = disk_x * f.u.y + disk_y * f.v.y;
    const float offset_z = disk_x * f.u.z + disk_y * f.v.z;
    // A pinhole's rays as generate_ray makes them, without the (zero) offset's signed zeros.
    const float lens_ox = f.origin.x + offset_x, lens_oy = f.origin.y + offset_y,
                lens_oz = f.origin.z + offset_z;
    const float lens_dx = film_x - offset_x, lens_dy = film_y - offset_y,
                lens_dz = film_z - offset_z;
    ox[k] = lens ? lens_ox : f.origin.x;
    oy[k] = lens ? lens_oy : f.origin.y;
    oz[k] = lens ? lens_oz : f.origin.z;
    dx[k] = lens ? lens_dx : film_x;
    dy[k] = lens ? lens_dy : film_y;
    dz[k] = lens ? lens_dz : film_z;
  }
  for (int k = 0; k < kLanes; ++k) out[k] = Ray{{ox[k], oy[k], oz[k]}, {dx[k], dy[k], dz[k]}};
}

}  // namespace

void Camera::generate_rays(const Lanes& in, Ray* out) const {
  lanes_to_rays({origin_, upper_left_, horizontal_, vertical_, u_, v_, lens_radius_}, in, out);
}

}  // namespace rtiow
