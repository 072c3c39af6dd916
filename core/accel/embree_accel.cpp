#include "core/accel/embree_accel.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

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

// Bounds of one sphere, padded by a few ulps: the box must contain every point the float
// sphere test can report, or Embree could skip a hit the naive loop finds.
void sphere_bounds(const RTCBoundsFunctionArguments* args) {
  const auto& s = *static_cast<const SphereSet*>(args->geometryUserPtr);
  tsan_acquire(&s);  // Embree's build threads start after the spheres were written
  const unsigned i = args->primID;
  const float r = std::abs(s.radius[i]);
  auto pad = [](float lo, float hi, float& out_lo, float& out_hi) {
    const float slack =
        4.0f * std::numeric_limits<float>::epsilon() * std::max(std::abs(lo), std::abs(hi));
    out_lo = lo - slack;
    out_hi = hi + slack;
  };
  RTCBounds* b = args->bounds_o;
  pad(s.center_x[i] - r, s.center_x[i] + r, b->lower_x, b->upper_x);
  pad(s.center_y[i] - r, s.center_y[i] + r, b->lower_y, b->upper_y);
  pad(s.center_z[i] - r, s.center_z[i] + r, b->lower_z, b->upper_z);
  tsan_release(&s);  // ...and finish before the commit returns
}

// Called by rtcIntersect1 for each sphere whose box the ray enters; N is 1 for single rays.
void sphere_intersect(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto& s = *static_cast<const SphereSet*>(args->geometryUserPtr);
  const unsigned i = args->primID;
  RTCRayHit* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
  const Ray ray{{rh->ray.org_x, rh->ray.org_y, rh->ray.org_z},
                {rh->ray.dir_x, rh->ray.dir_y, rh->ray.dir_z}};
  float t;
  if (!intersect_sphere(s.center(i), s.radius[i], ray, rh->ray.tnear, rh->ray.tfar, t)) return;
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

void sphere_occluded(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  const auto& s = *static_cast<const SphereSet*>(args->geometryUserPtr);
  const unsigned i = args->primID;
  RTCRay* r = reinterpret_cast<RTCRay*>(args->ray);
  const Ray ray{{r->org_x, r->org_y, r->org_z}, {r->dir_x, r->dir_y, r->dir_z}};
  float t;
  if (intersect_sphere(s.center(i), s.radius[i], ray, r->tnear, r->tfar, t)) {
    r->tfar = -std::numeric_limits<float>::infinity();  // Embree's "occluded" marker
  }
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
    rtcSetGeometryOccludedFunction(geometry, sphere_occluded);
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

bool EmbreeAccel::occluded(const Ray& ray, float t_max) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r;
  r.org_x = ray.origin.x;
  r.org_y = ray.origin.y;
  r.org_z = ray.origin.z;
  r.dir_x = ray.direction.x;
  r.dir_y = ray.direction.y;
  r.dir_z = ray.direction.z;
  r.tnear = 0.0f;
  r.tfar = t_max;
  r.time = 0.0f;
  r.mask = ~0u;
  r.id = 0;
  r.flags = 0;
  rtcOccluded1(scene_, &context, &r);
  return r.tfar < 0.0f;
}

}  // namespace rtiow
