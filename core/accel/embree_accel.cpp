#include "core/accel/embree_accel.h"

#include <cerrno>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/geometry/ray_offset.h"
#include "core/geometry/sphere_bounds.h"
#include "core/geometry/sphere_intersect.h"
#include "core/limits/error.h"
#include "core/limits/setting_name.h"
#include "core/parallel/cancellation.h"
#include "core/parallel/instruction_sets.h"
#include "core/parallel/thread_limit.h"
#include "core/parallel/thread_sanitizer.h"

namespace rtiow {
namespace {

// Embree's error in words: the name a user can look up, and what it usually means here.
std::string error_name(RTCError error) {
  switch (error) {
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory (RTC_ERROR_OUT_OF_MEMORY)";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "this CPU is not supported (RTC_ERROR_UNSUPPORTED_CPU)";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "RTC_ERROR_INVALID_ARGUMENT";
    case RTC_ERROR_INVALID_OPERATION:
      return "RTC_ERROR_INVALID_OPERATION";
    case RTC_ERROR_CANCELLED:
      return "RTC_ERROR_CANCELLED";
    default:
      return "RTC_ERROR_UNKNOWN (error " + std::to_string(int(error)) + ")";
  }
}

void throw_on_device_error(RTCDevice device, const char* what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE) {
    throw std::runtime_error(std::string("embree: ") + what + " failed: " + error_name(error));
  }
}

// Bounds of one sphere for Embree's build (the padding is explained in sphere_bounds.h).
void sphere_bounds(const RTCBoundsFunctionArguments* args) {
  const auto& s = *static_cast<const SphereSet*>(args->geometryUserPtr);
  tsan_acquire(&s);  // Embree's build threads start after the spheres were written
  const unsigned i = args->primID;
  RTCBounds* b = args->bounds_o;
  if (cancellation_requested()) {
    // An empty box (lower above upper): Embree drops the sphere, so a build being cancelled
    // skips the rest of its work; the scene is thrown away after the commit.
    b->lower_x = b->lower_y = b->lower_z = 1.0f;
    b->upper_x = b->upper_y = b->upper_z = -1.0f;
    tsan_release(&s);
    return;
  }
  const Box box = padded_sphere_bounds(s.center(i), s.radius[i]);
  b->lower_x = box.lower.x, b->lower_y = box.lower.y, b->lower_z = box.lower.z;
  b->upper_x = box.upper.x, b->upper_y = box.upper.y, b->upper_z = box.upper.z;
  tsan_release(&s);  // ...and finish before the commit returns
}

// Whether a sphere found at t (infinity: not hit) replaces the hit so far (tfar, and `prim`
// when `has_hit`). Up to and including tfar: a sphere at exactly the distance of the hit so
// far (coincident spheres) wins if its index is lower, as in the naive loop, whatever order
// the traversal visits them in.
inline bool replaces(float t, float tfar, bool has_hit, unsigned i, unsigned prim) {
  return t < tfar || (t == tfar && has_hit && i < prim);
}

// The distance at which sphere i replaces the hit found so far, or infinity. Forced inline
// into the callback: GCC kept it out of line (18% of a render's profile as its own symbol),
// and inlined it is 1% faster.
[[gnu::always_inline]] inline float replacing_hit(const SphereSet& s, unsigned i, const Ray& ray,
                                                  float tnear, float tfar, bool has_hit,
                                                  unsigned prim) {
  const float t = sphere_hit_distance(s.center(i), s.radius[i], ray, tnear, next_float_up(tfar));
  return replaces(t, tfar, has_hit, i, prim) ? t : std::numeric_limits<float>::infinity();
}

// A camera packet's eight rays against sphere i, the exact test in SIMD lanes (a scalar
// test per ray was 2.3x the lean tracer's callback time on camera rays).
void packet_intersect(const SphereSet& s, unsigned i, const RTCIntersectFunctionNArguments* args) {
  constexpr int kLanes = EmbreeAccel::kPacketSize;
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, kLanes);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, kLanes);
  float* tfar = &RTCRayN_tfar(rays, kLanes, 0);
  alignas(32) float t_max[kLanes];
  alignas(32) float t[kLanes];
  for (int k = 0; k < kLanes; ++k) t_max[k] = next_float_up(tfar[k]);
  const float* dx = &RTCRayN_dir_x(rays, kLanes, 0);
  const float* dy = &RTCRayN_dir_y(rays, kLanes, 0);
  const float* dz = &RTCRayN_dir_z(rays, kLanes, 0);
  const double* inv_a =
      reinterpret_cast<const EmbreeAccel::SkippingContext*>(args->context)->packet_inv_a;
  alignas(64) double own_inv_a[kLanes];
  if (!inv_a) {  // a packet that did not come from intersect_packet
    inverse_length_squared<kLanes>(dx, dy, dz, own_inv_a);
    inv_a = own_inv_a;
  }
  const RayLanes<kLanes> lanes{{&RTCRayN_org_x(rays, kLanes, 0), &RTCRayN_org_y(rays, kLanes, 0),
                                &RTCRayN_org_z(rays, kLanes, 0)},
                               {dx, dy, dz},
                               &RTCRayN_tnear(rays, kLanes, 0),
                               t_max,
                               inv_a};
  if (!sphere_hit_distances_exact(s.center(i), s.radius[i], lanes, args->valid, t)) return;
  for (int k = 0; k < kLanes; ++k) {
    if (!args->valid[k] || t[k] == std::numeric_limits<float>::infinity()) continue;
    const bool has_hit = RTCHitN_geomID(hits, kLanes, k) != RTC_INVALID_GEOMETRY_ID;
    if (!replaces(t[k], tfar[k], has_hit, i, RTCHitN_primID(hits, kLanes, k))) continue;
    tfar[k] = t[k];
    RTCHitN_primID(hits, kLanes, k) = i;
    RTCHitN_geomID(hits, kLanes, k) = args->geomID;
    RTCHitN_instID(hits, kLanes, k, 0) = args->context->instID[0];
  }
}

// Called for each sphere whose box a ray enters: N = 1 for rtcIntersect1, 8 for the camera
// rays of rtcIntersect8 (the rays of the packet that entered it are `valid`); any other N
// (Embree's to choose) one ray at a time.
RTIOW_DISPATCHED void sphere_intersect(const RTCIntersectFunctionNArguments* args) {
  const auto& s = *static_cast<const SphereSet*>(args->geometryUserPtr);
  const unsigned i = args->primID;
  // The context is the one EmbreeAccel passed, extended (Embree's documented way).
  if (i == reinterpret_cast<const EmbreeAccel::SkippingContext*>(args->context)->skip) return;
  constexpr float kNone = std::numeric_limits<float>::infinity();
  if (args->N == 1) {
    if (!args->valid[0]) return;
    RTCRayHit* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
    const Ray ray{{rh->ray.org_x, rh->ray.org_y, rh->ray.org_z},
                  {rh->ray.dir_x, rh->ray.dir_y, rh->ray.dir_z}};
    const float t = replacing_hit(s, i, ray, rh->ray.tnear, rh->ray.tfar,
                                  rh->hit.geomID != RTC_INVALID_GEOMETRY_ID, rh->hit.primID);
    if (t == kNone) return;
    rh->ray.tfar = t;
    rh->hit.primID = i;
    rh->hit.geomID = args->geomID;
    rh->hit.instID[0] = args->context->instID[0];
    // u, v and Ng are left as they are: the integrator derives the normal from the sphere.
    return;
  }
  if (args->N == unsigned(EmbreeAccel::kPacketSize)) return packet_intersect(s, i, args);
  const unsigned n = args->N;
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, n);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, n);
  for (unsigned k = 0; k < n; ++k) {
    if (!args->valid[k]) continue;
    const Ray ray{
        {RTCRayN_org_x(rays, n, k), RTCRayN_org_y(rays, n, k), RTCRayN_org_z(rays, n, k)},
        {RTCRayN_dir_x(rays, n, k), RTCRayN_dir_y(rays, n, k), RTCRayN_dir_z(rays, n, k)}};
    const float t = replacing_hit(s, i, ray, RTCRayN_tnear(rays, n, k), RTCRayN_tfar(rays, n, k),
                                  RTCHitN_geomID(hits, n, k) != RTC_INVALID_GEOMETRY_ID,
                                  RTCHitN_primID(hits, n, k));
    if (t == kNone) continue;
    RTCRayN_tfar(rays, n, k) = t;
    RTCHitN_primID(hits, n, k) = i;
    RTCHitN_geomID(hits, n, k) = args->geomID;
    RTCHitN_instID(hits, n, k, 0) = args->context->instID[0];
  }
}

// The traversal-only callback (EmbreeCallback::Nothing).
void no_intersection(const RTCIntersectFunctionNArguments*) {}

}  // namespace

EmbreeAccel::EmbreeAccel(const SphereSet& spheres, EmbreeCallback callback) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) {
    // A failed creation leaves its error with the thread (rtcGetDeviceError(NULL)).
    throw std::runtime_error("embree: cannot create a device: " +
                             error_name(rtcGetDeviceError(nullptr)));
  }
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
    rtcSetGeometryIntersectFunction(
        geometry, callback == EmbreeCallback::Nothing ? no_intersection : sphere_intersect);
    rtcCommitGeometry(geometry);
    tsan_release(&spheres);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    // A build of millions of spheres takes a while: it stops when a stop is asked for.
    rtcSetSceneProgressMonitorFunction(
        scene_, [](void*, double) { return !cancellation_requested(); }, nullptr);
    rtcCommitScene(scene_);
    tsan_acquire(&spheres);
    throw_if_cancelled();
    if (rtcGetDeviceError(device_) == RTC_ERROR_UNKNOWN && !a_thread_can_start()) {
      // TBB could not start a worker for the build (Embree reports that as "unknown"); the
      // device is left unreleased, since releasing it would try to start one again.
      device_ = nullptr;
      throw std::runtime_error(
          "embree: cannot start the threads the BVH's build needs: " + system_error_text(EAGAIN) +
          "; " + setting("threads", "1") + " needs none");
    }
    throw_on_device_error(device_, "building the sphere BVH");
  } catch (...) {
    if (device_) {
      if (scene_) rtcReleaseScene(scene_);
      rtcReleaseDevice(device_);
    }
    throw;
  }
}

void EmbreeAccel::intersect_packet(const Ray* rays, int count, std::optional<Hit>* hits) const {
  SkippingContext context;
  rtcInitIntersectContext(&context.embree);
  context.embree.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  context.skip = kNoSphere;
  alignas(32) int valid[kPacketSize];
  alignas(32) RTCRayHit8 packet;
  for (int k = 0; k < kPacketSize; ++k) {
    const bool active = k < count;
    valid[k] = active ? -1 : 0;
    const Ray& ray = rays[active ? k : 0];
    packet.ray.org_x[k] = ray.origin.x;
    packet.ray.org_y[k] = ray.origin.y;
    packet.ray.org_z[k] = ray.origin.z;
    packet.ray.dir_x[k] = ray.direction.x;
    packet.ray.dir_y[k] = ray.direction.y;
    packet.ray.dir_z[k] = ray.direction.z;
    packet.ray.tnear[k] = 0.0f;
    packet.ray.tfar[k] = std::numeric_limits<float>::infinity();
    packet.ray.time[k] = 0.0f;
    packet.ray.mask[k] = ~0u;
    packet.ray.id[k] = unsigned(k);
    packet.ray.flags[k] = 0;
    packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  }
  // Each ray's 1/|d|^2 once, not once for every sphere it meets.
  alignas(64) double inv_a[kPacketSize];
  inverse_length_squared<kPacketSize>(packet.ray.dir_x, packet.ray.dir_y, packet.ray.dir_z, inv_a);
  context.packet_inv_a = inv_a;
  rtcIntersect8(valid, scene_, &context.embree, &packet);
  for (int k = 0; k < count; ++k) {
    hits[k] = packet.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID
                  ? std::nullopt
                  : std::optional<Hit>(Hit{packet.ray.tfar[k], packet.hit.primID[k]});
  }
}

EmbreeAccel::~EmbreeAccel() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

}  // namespace rtiow
