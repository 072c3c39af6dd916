#pragma once
// Embree BVH over the scene's spheres: ONE geometry of type RTC_GEOMETRY_TYPE_USER whose
// bounds and intersect callbacks call the shared sphere test.

#include <embree3/rtcore.h>

#include <cstdint>
#include <optional>

#include "core/geometry/hit.h"
#include "core/geometry/ray.h"
#include "core/geometry/sphere_set.h"

namespace rtiow {

// What the intersect callback does. `Nothing` returns at once, so no hit is ever found: it
// measures Embree's traversal and call alone (`rtiow bench`), a ceiling for the renderer.
enum class EmbreeCallback { SphereTest, Nothing };

class EmbreeAccel {
 public:
  // Builds and commits the BVH. The spheres must outlive the accelerator.
  explicit EmbreeAccel(const SphereSet& spheres,
                       EmbreeCallback callback = EmbreeCallback::SphereTest);
  ~EmbreeAccel();
  EmbreeAccel(const EmbreeAccel&) = delete;
  EmbreeAccel& operator=(const EmbreeAccel&) = delete;

  static constexpr const char* name() { return "embree"; }

  // Embree's context, extended with the sphere to leave out (its callback reads it back).
  struct SkippingContext {
    RTCIntersectContext embree;
    std::uint32_t skip;
    const double* packet_inv_a = nullptr;  // a camera packet's 1/|d|^2 per ray, else null
  };

  // Closest hit with 0 < t < t_max, through rtcIntersect1.
  std::optional<Hit> intersect(const Ray& ray, float t_max, std::uint32_t skip = kNoSphere) const {
    SkippingContext context;
    rtcInitIntersectContext(&context.embree);
    context.skip = skip;
    RTCRayHit rh;
    rh.ray.org_x = ray.origin.x;
    rh.ray.org_y = ray.origin.y;
    rh.ray.org_z = ray.origin.z;
    rh.ray.dir_x = ray.direction.x;
    rh.ray.dir_y = ray.direction.y;
    rh.ray.dir_z = ray.direction.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = t_max;
    rh.ray.time = 0.0f;
    rh.ray.mask = ~0u;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context.embree, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    return Hit{rh.ray.tfar, rh.hit.primID};
  }

  // The closest hits (0 < t < infinity) of up to kPacketSize coherent rays at once (a
  // pixel's camera rays), through rtcIntersect8: the same hits as one by one, bit for bit
  // (the callback breaks ties by index, so the order Embree visits spheres in is moot).
  static constexpr int kPacketSize = 8;
  void intersect_packet(const Ray* rays, int count, std::optional<Hit>* hits) const;

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace rtiow
