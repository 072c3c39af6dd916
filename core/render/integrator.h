#pragma once
// The book's path tracer as an iterative loop: follow one path for at most `max_depth`
// rays, multiplying the throughput by each material's attenuation, until it escapes to
// the background or is absorbed. No recursion, no allocation.

#include <cstdint>
#include <limits>
#include <optional>

#include "core/accel/accelerator.h"
#include "core/geometry/ray_offset.h"
#include "core/scene/scene.h"

namespace rtiow {

template <Accelerator Accel>
Color trace_path(const Scene& scene, const Accel& accel, Ray ray, int max_depth, SampleStream& rng,
                 std::uint64_t& rays_traced) {
  Color throughput{1.0f, 1.0f, 1.0f};
  std::uint32_t left_behind = kNoSphere;  // the sphere the ray leaves outward, if any
  for (int depth = 0; depth < max_depth; ++depth) {
    if (!is_traceable(ray)) return Color{};
    ++rays_traced;
    const std::optional<Hit> hit =
        accel.intersect(ray, std::numeric_limits<float>::infinity(), left_behind);
    if (!hit) return throughput * scene.background(ray.direction);
    const SurfaceHit surface = make_surface_hit(scene.spheres, ray, *hit);
    const std::optional<Scattered> scattered =
        scatter(scene.materials[surface.material], ray.direction, surface, rng);
    if (!scattered) return Color{};  // absorbed
    throughput *= scattered->attenuation;
    ray = spawn_ray(surface, scattered->direction);
    left_behind = leaves_outward(surface, scattered->direction, scene.spheres.radius[hit->sphere])
                      ? hit->sphere
                      : kNoSphere;
  }
  return Color{};  // the depth limit: the book counts the path as black
}

}  // namespace rtiow
