#include "core/accel/embree_accel.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/geometry/ray_offset.h"
#include "core/geometry/sphere_bounds.h"
#include "core/geometry/sphere_intersect.h"
#include "core/render/thread_sanitizer.h"

namespace rtiow {
namespace {

void throw_on_device_error(RTCDevice device, const char* what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE) {
    throw std::runtime_error(std::string("embree: ") + what + " failed (error " +
                             std::to_string(int(error)) + ")");
  }
}

// Bounds of one sphere for Embree's build (the padding is explained in sphere_bounds.h).
void sphere_bounds(const RTCBoundsFunctionArguments* args) {
  const auto& s = *static_cast<const SphereSet*>(args->geometryUserPtr);
  tsan_acquire(&s);  // Embree's build threads start after the spheres were written
  const unsigned i = args->primID;
  const Box box = padded_sphere_bounds(s.center(i), s.radius[i]);
  RTCBounds* b = args->bounds_o;
  b->lower_x = box.lower.x, b->lower_y = box.lower.y, b->lower_z = box.lower.z;
  b->upper_x = box.upper.x, b->upper_y = box.upper.y, b->upper_z = box.upper.z;
  tsan_release(&s);  // ...and finish before the commit returns
}

// Called by rtcIntersect1 for each sphere whose box the ray enters; N is 1 for single rays.
void sphere_intersect(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto& s = *static_cast<const SphereSet*>(args->geometryUserPtr);
  const unsigned i = args->primID;
  // The context is the one EmbreeAccel::intersect passed, extended (Embree's documented way).
  if (i == reinterpret_cast<const EmbreeAccel::SkippingContext*>(args->context)->skip) return;
  RTCRayHit* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
  const Ray ray{{rh->ray.org_x, rh->ray.org_y, rh->ray.org_z},
                {rh->ray.dir_x, rh->ray.dir_y, rh->ray.dir_z}};
  // Up to and including tfar: a sphere at exactly the distance of the hit found so far
  // (coincident spheres) wins if its index is lower, as in the naive loop, whatever order
  // the traversal visits them in.
  const float t = sphere_hit_distance(s.center(i), s.radius[i], ray, rh->ray.tnear,
                                      next_float_up(rh->ray.tfar));
  const bool closer = t < rh->ray.tfar;
  const bool tie_won =
      t == rh->ray.tfar && rh->hit.geomID != RTC_INVALID_GEOMETRY_ID && i < rh->hit.primID;
  if (!closer && !tie_won) return;
  rh->ray.tfar = t;
  rh->hit.u = 0.0f;
  rh->hit.v = 0.0f;
  rh->hit.Ng_x = 0.0f;  // the integrator derives the normal from the sphere
  rh->hit.Ng_y = 0.0f;
  rh->hit.Ng_z = 0.0f;
  rh->hit.primID = i;
  rh->hit.geomID = args->geomID;
  rh->hit.instID[0] = args->context->instID[0];
}

}  // namespace

EmbreeAccel::EmbreeAccel(const SphereSet& spheres) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("embree: cannot create a device");
  try {
    scene_ = rtcNewScene(device_);
    // ROBUST: conservative box tests, so no sphere whose box the ray grazes is skipped;
    // needed for the promise that Embree and the naive loop find the same hits.
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);

    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(spheres.size()));
    rtcSetGeometryUserData(geometry, const_cast<SphereSet*>(&spheres));
    rtcSetGeometryBoundsFunction(geometry, sphere_bounds, nullptr);
    rtcSetGeometryIntersectFunction(geometry, sphere_intersect);
    rtcCommitGeometry(geometry);
    tsan_release(&spheres);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene_);
    tsan_acquire(&spheres);
    throw_on_device_error(device_, "building the sphere BVH");
  } catch (...) {
    if (scene_) rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
    throw;
  }
}

EmbreeAccel::~EmbreeAccel() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

}  // namespace rtiow
