#include "core/geometry/sphere_intersect.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/geometry/sphere_bounds.h"
#include "core/sampling/rng.h"

namespace rtiow {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// The box an accelerator culls with holds the whole sphere, exactly, and every hit point the
// float test reports, grazing ones included (an unpadded box rounds half of its faces inward).
TEST(SphereBounds, HoldTheExactSphereAndEveryReportedHit) {
  Pcg32 rng(42, 7);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const float scale = std::pow(10.0f, 4.0f * rng.next_float());
    const Vec3 center{scale * (rng.next_float() - 0.5f), scale * (rng.next_float() - 0.5f),
                      scale * (rng.next_float() - 0.5f)};
    const float radius = std::pow(10.0f, 3.0f * rng.next_float() - 1.0f);
    const Box box = padded_sphere_bounds(center, radius);
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const double c = double(center[axis]), r = double(radius);
      ASSERT_LE(double(box.lower[axis]), c - r) << i;
      ASSERT_GE(double(box.upper[axis]), c + r) << i;
    }
    // A ray towards a point just inside the silhouette, seen from a random direction.
    const Vec3 from =
        center + 3.0f * radius * Vec3{rng.next_float() - 0.5f, 1.0f, rng.next_float() - 0.5f};
    const Vec3 side = normalize(cross(center - from, Vec3{1, 0, 0}));
    const Vec3 target = center + (radius * (1.0f - 1e-4f * rng.next_float())) * side;
    const Ray ray{from, target - from};
    float t = 0;
    if (!intersect_sphere(center, radius, ray, 0.0f, kInf, t)) continue;
    ++hits;
    const Vec3 p = ray.origin + t * ray.direction;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      ASSERT_LE(box.lower[axis], p[axis]) << i;
      ASSERT_GE(box.upper[axis], p[axis]) << i;
    }
  }
  EXPECT_GT(hits, 10000);
}

TEST(SphereIntersect, HitsFromOutsideAtTheNearRoot) {
  float t = 0;
  const Ray ray{{0, 0, 5}, {0, 0, -1}};
  ASSERT_TRUE(intersect_sphere(Vec3{0, 0, 0}, 1.0f, ray, 0.0f, kInf, t));
  EXPECT_FLOAT_EQ(t, 4.0f);
}

TEST(SphereIntersect, UnnormalisedDirectionsScaleT) {
  float t = 0;
  const Ray ray{{0, 0, 5}, {0, 0, -2}};
  ASSERT_TRUE(intersect_sphere(Vec3{0, 0, 0}, 1.0f, ray, 0.0f, kInf, t));
  EXPECT_FLOAT_EQ(t, 2.0f);
}

TEST(SphereIntersect, Misses) {
  float t = 0;
  EXPECT_FALSE(intersect_sphere(Vec3{0, 0, 0}, 1.0f, Ray{{0, 2, 5}, {0, 0, -1}}, 0.0f, kInf, t));
  // Sphere behind the origin.
  EXPECT_FALSE(intersect_sphere(Vec3{0, 0, 0}, 1.0f, Ray{{0, 0, 5}, {0, 0, 1}}, 0.0f, kInf, t));
  // Sphere beyond t_max.
  EXPECT_FALSE(intersect_sphere(Vec3{0, 0, 0}, 1.0f, Ray{{0, 0, 5}, {0, 0, -1}}, 0.0f, 3.9f, t));
}

TEST(SphereIntersect, FromInsideHitsTheFarRoot) {
  float t = 0;
  ASSERT_TRUE(intersect_sphere(Vec3{0, 0, 0}, 2.0f, Ray{{0, 0, 0}, {1, 0, 0}}, 0.0f, kInf, t));
  EXPECT_FLOAT_EQ(t, 2.0f);
  ASSERT_TRUE(intersect_sphere(Vec3{0, 0, 0}, 2.0f, Ray{{0, 1, 0}, {0, 1, 0}}, 0.0f, kInf, t));
  EXPECT_FLOAT_EQ(t, 1.0f);
}

TEST(SphereIntersect, TangentRayTouchesOnce) {
  float t = 0;
  // Grazes the top of the unit sphere at (0, 1, 0).
  ASSERT_TRUE(intersect_sphere(Vec3{0, 0, 0}, 1.0f, Ray{{-3, 1, 0}, {1, 0, 0}}, 0.0f, kInf, t));
  EXPECT_FLOAT_EQ(t, 3.0f);
  EXPECT_FALSE(
      intersect_sphere(Vec3{0, 0, 0}, 1.0f, Ray{{-3, 1.0001f, 0}, {1, 0, 0}}, 0.0f, kInf, t));
}

TEST(SphereIntersect, NegativeRadiusIntersectsLikeItsMagnitude) {
  float a = 0, b = 0;
  const Ray ray{{0.1f, 0.2f, 5}, {0, 0, -1}};
  ASSERT_TRUE(intersect_sphere(Vec3{0, 0, 0}, 0.4f, ray, 0.0f, kInf, a));
  ASSERT_TRUE(intersect_sphere(Vec3{0, 0, 0}, -0.4f, ray, 0.0f, kInf, b));
  EXPECT_EQ(a, b);
}

// The careful form keeps float accurate where the textbook discriminant b^2 - 4ac cancels:
// small spheres far from the ray origin. Compare float with the double evaluation.
TEST(SphereIntersect, FloatStaysAccurateForSmallDistantSpheres) {
  Pcg32 rng(1, 2);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const double distance = std::pow(10.0, 1.0 + 4.0 * rng.next_double());
    const double radius = distance * std::pow(10.0, -4.0 - 2.0 * rng.next_double());
    const Vec3d center{distance, 0.0, 0.0};
    // Aim inside the sphere's silhouette.
    const Vec3d target = center + Vec3d{0.0, 0.9 * radius * (2 * rng.next_double() - 1), 0.0};
    const Rayd ray_d{{0, 0, 0}, normalize(target)};
    const Ray ray_f{Vec3(ray_d.origin), Vec3(ray_d.direction)};
    double t_d;
    float t_f;
    if (!intersect_sphere(center, radius, ray_d, 0.0, 1e30, t_d)) continue;
    ++hits;
    ASSERT_TRUE(intersect_sphere(Vec3(center), float(radius), ray_f, 0.0f, kInf, t_f))
        << "float missed a sphere of radius " << radius << " at " << distance;
    // Within a few ulps of the distance, relative to the size of the coordinates.
    EXPECT_LT(std::abs(double(t_f) - t_d),
              64 * double(std::numeric_limits<float>::epsilon()) * distance);
  }
  EXPECT_GT(hits, 15000);
}

// The SIMD lanes of a camera packet give each ray what the scalar test (with its float
// pre-test) gives it, bit for bit: from outside, inside, on the surface, grazing, behind,
// for hollow, tiny and huge spheres, and with t ranges that cut the roots.
TEST(SphereIntersect, LanesGiveTheScalarTestBitForBit) {
  Pcg32 rng(31, 7);
  auto uniform = [&](float lo, float hi) { return lo + (hi - lo) * rng.next_float(); };
  constexpr int kLanes = 8;
  int hits = 0, cases = 0, skipped = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const float scale = std::pow(10.0f, uniform(-3.0f, 6.0f));
    const Vec3 center{uniform(-1, 1) * scale, uniform(-1, 1) * scale, uniform(-1, 1) * scale};
    const float radius = (trial % 5 == 0 ? -1.0f : 1.0f) * scale * uniform(0.01f, 1.5f);
    float ox[kLanes], oy[kLanes], oz[kLanes], dx[kLanes], dy[kLanes], dz[kLanes];
    float t_min[kLanes], t_max[kLanes], t[kLanes];
    for (int k = 0; k < kLanes; ++k) {
      // Origins anywhere near the sphere, on its surface, or in it; directions at its
      // centre, past it, or away.
      const Vec3 spread{uniform(-2, 2), uniform(-2, 2), uniform(-2, 2)};
      const float r = std::abs(radius);
      const Vec3 origin = k % 3 == 0 ? center + (r / length(spread)) * spread
                                     : center + (k % 3 == 1 ? 0.5f : 3.0f) * r * spread;
      const Vec3 aim =
          center + r * Vec3{uniform(-1.2f, 1.2f), uniform(-1.2f, 1.2f), uniform(-1.2f, 1.2f)};
      const Vec3 direction = (trial + k) % 7 == 0 ? origin - aim : aim - origin;
      ox[k] = origin.x, oy[k] = origin.y, oz[k] = origin.z;
      dx[k] = direction.x, dy[k] = direction.y, dz[k] = direction.z;
      t_min[k] = k % 4 == 0 ? uniform(0.0f, 1.0f) : 0.0f;
      t_max[k] = k % 2 == 0 ? kInf : uniform(0.2f, 2.0f);
      // Bounds exactly at a root, where the strict comparisons decide.
      const float root = sphere_hit_distance(center, radius, Ray{origin, direction}, 0.0f, kInf);
      if (k % 4 == 1 && root < kInf) t_min[k] = root;
      if (k % 4 == 3 && root < kInf) t_max[k] = root;
    }
    double inv_a[kLanes];
    inverse_length_squared<kLanes>(dx, dy, dz, inv_a);
    const RayLanes<kLanes> lanes{{ox, oy, oz}, {dx, dy, dz}, t_min, t_max, inv_a};
    // Embree's valid mask: every lane, or some (then only they count for leaving early).
    int active[kLanes];
    for (int k = 0; k < kLanes; ++k) active[k] = trial % 3 == 0 || rng.next_float() < 0.5f ? -1 : 0;
    const bool tested = sphere_hit_distances_exact(center, radius, lanes, active, t);
    skipped += !tested;
    for (int k = 0; k < kLanes; ++k) {
      const Ray ray{{ox[k], oy[k], oz[k]}, {dx[k], dy[k], dz[k]}};
      const float scalar = sphere_hit_distance(center, radius, ray, t_min[k], t_max[k]);
      if (!tested) {  // left early: no active lane may have a hit
        if (active[k]) {
          ASSERT_EQ(scalar, kInf) << "trial " << trial << " lane " << k;
        }
        continue;
      }
      ASSERT_EQ(std::bit_cast<std::uint32_t>(t[k]), std::bit_cast<std::uint32_t>(scalar))
          << "trial " << trial << " lane " << k << ": " << t[k] << " against " << scalar;
      hits += scalar < kInf;
      ++cases;
    }
  }
  EXPECT_GT(hits, cases / 4);
  EXPECT_LT(hits, cases * 3 / 4);
  EXPECT_GT(skipped, 100);  // the early way out is taken, and checked above
}

// A packet whose every ray passes beside the sphere leaves before the square roots; one ray
// that grazes it is enough to test them all.
TEST(SphereIntersect, LanesLeaveEarlyOnlyWhenNoActiveRayCanHit) {
  constexpr int kLanes = 8;
  float ox[kLanes], oy[kLanes], oz[kLanes], dx[kLanes], dy[kLanes], dz[kLanes];
  float t_min[kLanes], t_max[kLanes], t[kLanes];
  int active[kLanes];
  for (int k = 0; k < kLanes; ++k) {
    ox[k] = -5, oy[k] = 1.5f + float(k), oz[k] = 0, dx[k] = 1, dy[k] = 0, dz[k] = 0;
    t_min[k] = 0, t_max[k] = kInf, active[k] = -1;
  }
  double inv_a[kLanes];
  inverse_length_squared<kLanes>(dx, dy, dz, inv_a);
  const RayLanes<kLanes> lanes{{ox, oy, oz}, {dx, dy, dz}, t_min, t_max, inv_a};
  EXPECT_FALSE(sphere_hit_distances_exact(Vec3{0, 0, 0}, 1.0f, lanes, active, t));
  oy[5] = 1.0f;  // grazes the top
  ASSERT_TRUE(sphere_hit_distances_exact(Vec3{0, 0, 0}, 1.0f, lanes, active, t));
  EXPECT_EQ(t[5], 5.0f);
  EXPECT_EQ(t[0], kInf);
  active[5] = 0;  // a grazing ray outside the box Embree tested does not count
  EXPECT_FALSE(sphere_hit_distances_exact(Vec3{0, 0, 0}, 1.0f, lanes, active, t));
}

}  // namespace
}  // namespace rtiow
