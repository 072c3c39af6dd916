#pragma once
// The book's path tracer as an iterative loop: follow one path for at most `max_depth`
// rays, multiplying the throughput by each material's attenuation, until it escapes to
// the background, is absorbed or, carrying almost nothing, loses the Russian roulette
// (core/render/russian_roulette.h). No recursion, no allocation. The first ray is traced by
// the sample loop (core/render/render_loop.h), with other samples' first rays in a packet.

#include <cstdint>
#include <limits>
#include <optional>

#include "core/accel/accelerator.h"
#include "core/film/first_hit_sum.h"
#include "core/geometry/ray_offset.h"
#include "core/render/russian_roulette.h"
#include "core/sampling/sampler.h"
#include "core/scene/scene.h"

namespace rtiow {

// What a camera ray first met, for the passes: the material's albedo, the normal it shades with
// and the distance from the ray's origin (all zero for the sky, FirstHit{}).
inline FirstHit first_hit(const Material& material, const SurfaceHit& surface, const Ray& ray) {
  const Vec3d offset = Vec3d(surface.point) - Vec3d(ray.origin);
  return {albedo(material), surface.normal, float(length(offset))};
}

// Follows a path on from its first ray, already traced (and counted): `hit` is what it hit.
// Without `russian_roulette` it runs to `max_depth` (or its end) as the book's paths do. With
// `first`, what the first ray met is kept there (the passes'), from the surface the path
// scatters at rather than worked out again from the hit.
// Inlined into the sample loop, so that it is compiled for each of the loop's instruction sets
// (core/parallel/instruction_sets.h) rather than once for the baseline.
template <Accelerator Accel>
[[gnu::always_inline]] inline Color continue_path(const Scene& scene, const Accel& accel, Ray ray,
                                                  std::optional<Hit> hit, int max_depth,
                                                  bool russian_roulette, SampleStream& rng,
                                                  std::uint64_t& rays_traced,
                                                  FirstHit* first = nullptr) {
  Color throughput{1.0f, 1.0f, 1.0f};
  for (int depth = 1;; ++depth) {
    if (!hit) return throughput * scene.background(ray.direction);
    // Every bounce takes the same dimensions whatever it hits (core/sampling/sample_layout.h);
    // the sampler computes only those the material reads. Drawn before the hit point, whose
    // square root and division it does not wait for.
    const Material& material = scene.materials[scene.spheres.material[hit->sphere]];
    const unsigned uses = bounce_uses(material);
    const bool plays = russian_roulette && plays_roulette(depth, throughput);
    const BounceSample u = rng.next_bounce(plays ? uses | roulette_use(uses) : uses);
    if (plays) {
      const std::optional<Color> goes_on = roulette(throughput, roulette_number(u, uses));
      if (!goes_on) return Color{};
      throughput = *goes_on;
    }
    const SurfaceHit surface = make_surface_hit(scene.spheres, ray, *hit);
    if (first && depth == 1) *first = first_hit(material, surface, ray);  // no roulette yet
    const std::optional<Scattered> scattered = scatter(material, ray.direction, surface, u);
    if (!scattered) return Color{};  // absorbed
    throughput *= scattered->attenuation;
    // The sphere the ray leaves outward, which it cannot hit again.
    const std::uint32_t left_behind =
        leaves_outward(surface, scattered->direction, scene.spheres.radius[hit->sphere])
            ? hit->sphere
            : kNoSphere;
    ray = spawn_ray(surface, scattered->direction);
    if (depth >= max_depth) return Color{};  // the depth limit: the book counts it black
    if (!is_traceable(ray)) return Color{};
    ++rays_traced;
    hit = accel.intersect(ray, std::numeric_limits<float>::infinity(), left_behind);
  }
}

// Whether a path's first ray is traced at all (a depth of 0, or a ray gone NaN, is black).
inline bool starts_path(const Ray& ray, int max_depth) {
  return max_depth > 0 && is_traceable(ray);
}

}  // namespace rtiow
