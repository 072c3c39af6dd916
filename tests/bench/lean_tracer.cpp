// A lean path tracer of rtiow's cover scene, for one comparison: what a render loop with no
// more than the book's program in it reaches through Embree on this machine, against which
// `rtiow bench-point` is measured (docs/performance.md). It takes rtiow's scene (spheres,
// materials, camera) and nothing else of rtiow: its own camera, materials, PCG32 stream per
// sample, float sums, the book's t_min of 0.001 and a double sphere test without rtiow's
// pre-test, tie rule or error bounds. Camera rays go to Embree eight at a time, like rtiow's.
// With --robust-offset a bounce starts as rtiow's do (the hit re-projected onto the sphere in
// double, the next ray just outside its error bound, t_min 0), in this file's own code: what
// that idea costs a lean loop, apart from the rest of rtiow.
//
//   build/bin/rtiow_lean_tracer [--width 400] [--height 225] [--spp 100] [--depth 50]
//                               [--threads 2] [--repeat 3] [--float] [--robust-offset]
// prints one JSON line: the median render rate of the repeats, in Mrays/s.

#include <embree3/rtcore.h>
#include <oneapi/tbb/blocked_range2d.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "core/scene/builtin_scenes.h"

namespace {

struct V3 {
  float x, y, z;
};
inline V3 operator+(V3 a, V3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline V3 operator-(V3 a, V3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline V3 operator*(float s, V3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
inline V3 operator*(V3 a, V3 b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
inline V3 operator-(V3 a) {
  return {-a.x, -a.y, -a.z};
}
inline float dot(V3 a, V3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline V3 unit(V3 a) {
  return (1.0f / std::sqrt(dot(a, a))) * a;
}

// PCG32 (O'Neill), one stream per sample.
struct Pcg {
  std::uint64_t state, inc;
  Pcg(std::uint64_t seed, std::uint64_t stream) : state(0), inc((stream << 1u) | 1u) {
    next();
    state += seed;
    next();
  }
  std::uint32_t next() {
    const std::uint64_t old = state;
    state = old * 6364136223846793005ull + inc;
    const auto xorshifted = std::uint32_t(((old >> 18u) ^ old) >> 27u);
    const auto rot = std::uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  float uniform() { return float(next() >> 8) * 0x1p-24f; }
};

V3 random_in_unit_sphere(Pcg& rng) {
  for (;;) {
    const V3 p{2 * rng.uniform() - 1, 2 * rng.uniform() - 1, 2 * rng.uniform() - 1};
    if (dot(p, p) < 1) return p;
  }
}
V3 random_unit_vector(Pcg& rng) {
  return unit(random_in_unit_sphere(rng));
}

struct Sphere {
  float x, y, z, r;
};
struct Mat {
  int kind;  // 0 lambertian, 1 metal, 2 dielectric
  V3 albedo;
  float fuzz, ior;
};

struct World {
  std::vector<Sphere> spheres;
  std::vector<std::uint32_t> material;
  std::vector<Mat> materials;
  bool double_test = true;
  bool robust_offset = false;
};

// The float next to v, away from zero when `up` is v's sign and toward it otherwise (v finite
// and not zero), by arithmetic on the bits: the side is random, a branch would mispredict.
float next_float(float v, bool up) {
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(v);
  const bool negative = (bits >> 31) != 0;
  return std::bit_cast<float>(bits + 1u - 2u * std::uint32_t(up == negative));
}

// Where the bounce's next ray starts with --robust-offset: the hit point o + t d re-projected
// onto sphere s in double, rounded to float, and moved along the normal past a bound on its
// error (half an ulp of the point, plus the double computation's few ulps of the centre and
// radius), to the side `next` leaves to, each component rounded away from the surface
// (Woop/Wächter & Binder, Ray Tracing Gems ch. 6; pbrt-v4 OffsetRayOrigin).
V3 robust_origin(const Sphere& s, V3 o, V3 d, float t, V3 next) {
  const double cx = s.x, cy = s.y, cz = s.z, r = std::abs(double(s.r));
  const double fx = double(o.x) + double(t) * double(d.x) - cx;
  const double fy = double(o.y) + double(t) * double(d.y) - cy;
  const double fz = double(o.z) + double(t) * double(d.z) - cz;
  const double inv_length = 1.0 / std::sqrt(fx * fx + fy * fy + fz * fz);
  const V3 n{float(fx * inv_length), float(fy * inv_length), float(fz * inv_length)};
  const V3 p{float(cx + r * fx * inv_length), float(cy + r * fy * inv_length),
             float(cz + r * fz * inv_length)};
  const float half_ulp = 0.5f * std::numeric_limits<float>::epsilon();
  const V3 error{half_ulp * std::abs(p.x) + float(1e-14 * (std::abs(cx) + r)),
                 half_ulp * std::abs(p.y) + float(1e-14 * (std::abs(cy) + r)),
                 half_ulp * std::abs(p.z) + float(1e-14 * (std::abs(cz) + r))};
  float offset = std::abs(n.x) * error.x + std::abs(n.y) * error.y + std::abs(n.z) * error.z;
  if (dot(next, n) < 0.0f) offset = -offset;
  const V3 moved = p + offset * n;
  auto away = [](float q, float step) {
    return step != 0.0f && q != 0.0f ? next_float(q, step > 0.0f) : q;
  };
  return {away(moved.x, offset * n.x), away(moved.y, offset * n.y), away(moved.z, offset * n.z)};
}

template <typename T>
void sphere_test(const Sphere& s, float ox, float oy, float oz, float dx, float dy, float dz,
                 float tnear, float& tfar, bool& hit) {
  const T fx = T(ox) - T(s.x), fy = T(oy) - T(s.y), fz = T(oz) - T(s.z);
  const T a = T(dx) * T(dx) + T(dy) * T(dy) + T(dz) * T(dz);
  const T half_b = fx * T(dx) + fy * T(dy) + fz * T(dz);
  const T c = fx * fx + fy * fy + fz * fz - T(s.r) * T(s.r);
  const T disc = half_b * half_b - a * c;
  if (disc < 0) return;
  const T root = std::sqrt(disc);
  T t = (-half_b - root) / a;
  if (!(t > T(tnear) && t < T(tfar))) {
    t = (-half_b + root) / a;
    if (!(t > T(tnear) && t < T(tfar))) return;
  }
  tfar = float(t);
  hit = true;
}

void intersect(const RTCIntersectFunctionNArguments* args) {
  const World& w = *static_cast<const World*>(args->geometryUserPtr);
  const Sphere& s = w.spheres[args->primID];
  const unsigned n = args->N;
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, n);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, n);
  for (unsigned k = 0; k < n; ++k) {
    if (!args->valid[k]) continue;
    float& tfar = RTCRayN_tfar(rays, n, k);
    bool hit = false;
    const float ox = RTCRayN_org_x(rays, n, k), oy = RTCRayN_org_y(rays, n, k),
                oz = RTCRayN_org_z(rays, n, k), dx = RTCRayN_dir_x(rays, n, k),
                dy = RTCRayN_dir_y(rays, n, k), dz = RTCRayN_dir_z(rays, n, k);
    if (w.double_test) {
      sphere_test<double>(s, ox, oy, oz, dx, dy, dz, RTCRayN_tnear(rays, n, k), tfar, hit);
    } else {
      sphere_test<float>(s, ox, oy, oz, dx, dy, dz, RTCRayN_tnear(rays, n, k), tfar, hit);
    }
    if (!hit) continue;
    RTCHitN_primID(hits, n, k) = args->primID;
    RTCHitN_geomID(hits, n, k) = args->geomID;
  }
}

void bounds(const RTCBoundsFunctionArguments* args) {
  const World& w = *static_cast<const World*>(args->geometryUserPtr);
  const Sphere& s = w.spheres[args->primID];
  const float r = std::abs(s.r);
  *args->bounds_o = RTCBounds{s.x - r, s.y - r, s.z - r, 0, s.x + r, s.y + r, s.z + r, 0};
}

struct Cam {
  V3 origin, corner, horizontal, vertical, u, v;
  float lens_radius;
};

// One bounce: false when the path is absorbed.
bool scatter(const Mat& m, V3 dir, V3 point, V3 outward, Pcg& rng, V3& attenuation, V3& out) {
  const bool front = dot(dir, outward) < 0;
  const V3 normal = front ? outward : -outward;
  (void)point;
  if (m.kind == 0) {
    V3 d = normal + random_unit_vector(rng);
    if (std::abs(d.x) < 1e-8f && std::abs(d.y) < 1e-8f && std::abs(d.z) < 1e-8f) d = normal;
    out = d;
    attenuation = m.albedo;
    return true;
  }
  if (m.kind == 1) {
    const V3 u = unit(dir);
    V3 reflected = u - 2 * dot(u, normal) * normal;
    reflected = unit(reflected) + m.fuzz * random_unit_vector(rng);
    out = reflected;
    attenuation = m.albedo;
    return dot(reflected, normal) > 0;
  }
  const float eta = front ? 1.0f / m.ior : m.ior;
  const V3 u = unit(dir);
  const float cos_theta = std::min(dot(-u, normal), 1.0f);
  const float sin_theta = std::sqrt(1.0f - cos_theta * cos_theta);
  float r0 = (1 - eta) / (1 + eta);
  r0 = r0 * r0;
  const float schlick = r0 + (1 - r0) * std::pow(1 - cos_theta, 5.0f);
  if (eta * sin_theta > 1.0f || schlick > rng.uniform()) {
    out = u - 2 * dot(u, normal) * normal;
  } else {
    const V3 perp = eta * (u + cos_theta * normal);
    const V3 para = -std::sqrt(std::abs(1.0f - dot(perp, perp))) * normal;
    out = perp + para;
  }
  attenuation = {1, 1, 1};
  return true;
}

struct Tracer {
  const World& world;
  RTCScene scene;
  Cam cam;
  int width, height, spp, depth;

  void trace_pixel(int x, int y, std::uint64_t& rays, V3& sum) const {
    for (int s0 = 0; s0 < spp; s0 += 8) {
      const int count = std::min(8, spp - s0);
      alignas(32) int valid[8];
      alignas(32) RTCRayHit8 packet;
      Pcg* rng = static_cast<Pcg*>(alloca(sizeof(Pcg) * 8));
      for (int k = 0; k < 8; ++k) {
        valid[k] = k < count ? -1 : 0;
        const std::uint64_t sample = std::uint64_t(s0 + k);
        new (&rng[k]) Pcg((std::uint64_t(y) * 65536u + std::uint64_t(x)) * 1315423911u, sample);
        const float su = (float(x) + rng[k].uniform()) / float(width);
        const float tv = (float(y) + rng[k].uniform()) / float(height);
        V3 offset{0, 0, 0};
        if (cam.lens_radius > 0) {
          float px, py;
          do {
            px = 2 * rng[k].uniform() - 1;
            py = 2 * rng[k].uniform() - 1;
          } while (px * px + py * py >= 1);
          offset = cam.lens_radius * px * cam.u + cam.lens_radius * py * cam.v;
        }
        const V3 o = cam.origin + offset;
        const V3 d = cam.corner + su * cam.horizontal + tv * cam.vertical - offset;
        packet.ray.org_x[k] = o.x, packet.ray.org_y[k] = o.y, packet.ray.org_z[k] = o.z;
        packet.ray.dir_x[k] = d.x, packet.ray.dir_y[k] = d.y, packet.ray.dir_z[k] = d.z;
        packet.ray.tnear[k] = 0.001f;
        packet.ray.tfar[k] = INFINITY;
        packet.ray.time[k] = 0;
        packet.ray.mask[k] = ~0u;
        packet.ray.id[k] = unsigned(k);
        packet.ray.flags[k] = 0;
        packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
      }
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      rtcIntersect8(valid, scene, &context, &packet);
      rays += std::uint64_t(count);
      for (int k = 0; k < count; ++k) {
        V3 o{packet.ray.org_x[k], packet.ray.org_y[k], packet.ray.org_z[k]};
        V3 d{packet.ray.dir_x[k], packet.ray.dir_y[k], packet.ray.dir_z[k]};
        bool hit = packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
        float t = packet.ray.tfar[k];
        unsigned prim = packet.hit.primID[k];
        V3 throughput{1, 1, 1};
        V3 color{0, 0, 0};
        for (int bounce = 1;; ++bounce) {
          if (!hit) {
            const float a = 0.5f * (unit(d).y + 1.0f);
            color = throughput * ((1 - a) * V3{1, 1, 1} + a * V3{0.5f, 0.7f, 1.0f});
            break;
          }
          const Sphere& sp = world.spheres[prim];
          const V3 p = o + t * d;
          const V3 outward = (1.0f / sp.r) * (p - V3{sp.x, sp.y, sp.z});
          V3 attenuation, next;
          if (!scatter(world.materials[world.material[prim]], d, p, outward, rng[k], attenuation,
                       next)) {
            break;
          }
          throughput = throughput * attenuation;
          if (bounce >= depth) break;
          RTCRayHit rh;
          const V3 start = world.robust_offset ? robust_origin(sp, o, d, t, next) : p;
          rh.ray.org_x = start.x, rh.ray.org_y = start.y, rh.ray.org_z = start.z;
          rh.ray.dir_x = next.x, rh.ray.dir_y = next.y, rh.ray.dir_z = next.z;
          rh.ray.tnear = world.robust_offset ? 0.0f : 0.001f;
          rh.ray.tfar = INFINITY;
          rh.ray.time = 0;
          rh.ray.mask = ~0u;
          rh.ray.id = 0;
          rh.ray.flags = 0;
          rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
          RTCIntersectContext single;
          rtcInitIntersectContext(&single);
          rtcIntersect1(scene, &single, &rh);
          ++rays;
          o = p, d = next;
          hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
          t = rh.ray.tfar;
          prim = rh.hit.primID;
        }
        sum = sum + color;
      }
    }
  }
};

int arg(int argc, char** argv, const char* name, int fallback) {
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], name) == 0) return std::atoi(argv[i + 1]);
  }
  return fallback;
}

}  // namespace

int main(int argc, char** argv) {
  const int width = arg(argc, argv, "--width", 400), height = arg(argc, argv, "--height", 225);
  const int spp = arg(argc, argv, "--spp", 100), depth = arg(argc, argv, "--depth", 50);
  const int threads = arg(argc, argv, "--threads", 2), repeat = arg(argc, argv, "--repeat", 3);
  bool use_float = false, robust_offset = false;
  for (int i = 1; i < argc; ++i) {
    use_float = use_float || std::strcmp(argv[i], "--float") == 0;
    robust_offset = robust_offset || std::strcmp(argv[i], "--robust-offset") == 0;
  }

  const rtiow::Scene scene = rtiow::make_builtin_scene("cover", 0);
  World world;
  world.double_test = !use_float;
  world.robust_offset = robust_offset;
  for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
    world.spheres.push_back({scene.spheres.center_x[i], scene.spheres.center_y[i],
                             scene.spheres.center_z[i], scene.spheres.radius[i]});
    world.material.push_back(scene.spheres.material[i]);
  }
  for (const rtiow::Material& m : scene.materials) {
    Mat out{};
    if (const auto* l = std::get_if<rtiow::Lambertian>(&m)) {
      out = {0, {l->albedo.x, l->albedo.y, l->albedo.z}, 0, 1};
    } else if (const auto* me = std::get_if<rtiow::Metal>(&m)) {
      out = {1, {me->albedo.x, me->albedo.y, me->albedo.z}, me->fuzz, 1};
    } else {
      out = {2, {1, 1, 1}, 0, std::get<rtiow::Dielectric>(m).ior};
    }
    world.materials.push_back(out);
  }

  const rtiow::CameraSettings& cs = scene.camera;
  const double h = std::tan(cs.vfov_degrees * std::numbers::pi / 360.0);
  const double vh = 2 * h, vw = vh * double(width) / double(height);
  auto to = [](const rtiow::Vec3d& v) { return V3{float(v.x), float(v.y), float(v.z)}; };
  const V3 wv = unit(to(cs.lookfrom - cs.lookat));
  const V3 up = to(cs.vup);
  V3 uv{up.y * wv.z - up.z * wv.y, up.z * wv.x - up.x * wv.z, up.x * wv.y - up.y * wv.x};
  uv = unit(uv);
  const V3 vv{wv.y * uv.z - wv.z * uv.y, wv.z * uv.x - wv.x * uv.z, wv.x * uv.y - wv.y * uv.x};
  const float fd = float(rtiow::focus_distance_of(cs));
  Cam cam;
  cam.origin = to(cs.lookfrom);
  cam.horizontal = (fd * float(vw)) * uv;
  cam.vertical = (-fd * float(vh)) * vv;
  cam.corner = -0.5f * cam.horizontal - 0.5f * cam.vertical - fd * wv;
  cam.u = uv, cam.v = vv;
  cam.lens_radius = float(cs.aperture / 2);

  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene rscene = rtcNewScene(device);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geometry, unsigned(world.spheres.size()));
  rtcSetGeometryUserData(geometry, &world);
  rtcSetGeometryBoundsFunction(geometry, bounds, nullptr);
  rtcSetGeometryIntersectFunction(geometry, intersect);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(rscene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(rscene);

  const Tracer tracer{world, rscene, cam, width, height, spp, depth};
  std::vector<V3> image(std::size_t(width) * std::size_t(height));
  std::vector<double> rates;
  std::uint64_t total_rays = 0;
  tbb::task_arena arena(threads);
  for (int r = 0; r < repeat; ++r) {
    std::atomic<std::uint64_t> rays{0};
    const auto start = std::chrono::steady_clock::now();
    arena.execute([&] {
      tbb::parallel_for(
          tbb::blocked_range2d<int>(0, height, 16, 0, width, 16),
          [&](const tbb::blocked_range2d<int>& tile) {
            std::uint64_t tile_rays = 0;
            for (int y = tile.rows().begin(); y < tile.rows().end(); ++y) {
              for (int x = tile.cols().begin(); x < tile.cols().end(); ++x) {
                V3 sum{0, 0, 0};
                tracer.trace_pixel(x, y, tile_rays, sum);
                image[std::size_t(y) * std::size_t(width) + std::size_t(x)] =
                    (1.0f / float(spp)) * sum;
              }
            }
            rays += tile_rays;
          },
          tbb::simple_partitioner());
    });
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    rates.push_back(double(rays.load()) / seconds * 1e-6);
    total_rays = rays.load();
  }
  std::sort(rates.begin(), rates.end());
  double mean = 0;
  for (const V3& p : image) mean += double(p.x + p.y + p.z) / 3.0;
  mean /= double(image.size());
  std::printf(
      "{\"tracer\":\"lean\",\"sphere_test\":\"%s\",\"offset\":\"%s\",\"threads\":%d,"
      "\"rays\":%llu,\"mrays_per_second\":%.3f,\"image_mean\":%.5f}\n",
      use_float ? "float" : "double", robust_offset ? "robust" : "t_min", threads,
      static_cast<unsigned long long>(total_rays), rates[rates.size() / 2], mean);
  rtcReleaseScene(rscene);
  rtcReleaseDevice(device);
  return 0;
}
