#pragma once
// The book's positionable thin-lens camera. Settings are validated once; the basis is
// derived in double so large or tiny scenes keep their precision, and rays are float.

#include <optional>

#include "core/geometry/ray.h"
#include "core/geometry/vec3.h"

namespace rtiow {

struct CameraSettings {
  Vec3d lookfrom{0, 0, 0};
  Vec3d lookat{0, 0, -1};
  Vec3d vup{0, 1, 0};
  double vfov_degrees = 90.0;  // vertical field of view
  double aperture = 0.0;       // lens diameter; 0 is a pinhole
  // The distance to the plane in focus; unset: the distance from lookfrom to lookat, as a
  // scene file without "focus_distance" has it.
  std::optional<double> focus_distance;
};

// The distance in focus that `settings` ask for (set, or lookfrom to lookat).
double focus_distance_of(const CameraSettings& settings);

// The smallest focus distance: below it float film vectors lose their direction.
inline constexpr double kMinFocusDistance = 1e-12;

// Throws InvalidInput naming the offending setting: lookfrom == lookat, vup parallel to
// the view direction, vfov outside (0, 180), aperture < 0, a focus distance outside
// [kMinFocusDistance, limits::kMaxCoordinate], a position beyond limits::kMaxCoordinate.
void validate(const CameraSettings& settings);

// The same, and the camera rays of an image of this size must be traceable (every component
// within limits::kMaxRayComponent).
void validate(const CameraSettings& settings, int image_width, int image_height);

class Camera {
 public:
  Camera(const CameraSettings& settings, int image_width, int image_height);

  // The ray through film position (s, t) in [0,1]^2, s to the right, t downwards from the
  // top-left corner; (lens_u, lens_v) in [0,1)^2 pick the point on the lens.
  Ray generate_ray(float s, float t, float lens_u, float lens_v) const;

  // The same for kLanes rays at once, lane by lane in arrays (film s and t, lens u and v),
  // written without branches so the compiler runs the lanes in SIMD: the rays are those of
  // generate_ray, bit for bit (tested), at a fraction of its cost per ray. Every lane is
  // computed; the caller reads the ones it filled.
  static constexpr int kLanes = 8;
  struct Lanes {
    alignas(32) float s[kLanes], t[kLanes], lens_u[kLanes], lens_v[kLanes];
  };
  void generate_rays(const Lanes& in, Ray* out) const;

  bool has_lens() const { return lens_radius_ > 0.0f; }

  // A bound on the magnitude of any component of any ray's origin or direction.
  double max_ray_component() const;

 private:
  Vec3 origin_;
  Vec3 upper_left_;  // film corner at the focus distance
  Vec3 horizontal_, vertical_;
  Vec3 u_, v_;  // lens basis
  float lens_radius_ = 0.0f;
};

}  // namespace rtiow
