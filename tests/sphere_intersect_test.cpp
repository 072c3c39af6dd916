#include "core/geometry/sphere_intersect.h"

#include <gtest/gtest.h>

#include <cmath>
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

}  // namespace
}  // namespace rtiow
