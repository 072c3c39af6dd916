// Quantities the renderer models, pinned tightly enough that an error of about 1% fails:
// the sky's gradient, Schlick's and the exact Fresnel reflectance against formulas written
// out here in double, the glass's reflection frequency, the metal's fuzz radius and spread,
// and how far a spawned ray starts from the surface (no farther than its error bound needs).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/geometry/ray_offset.h"
#include "core/geometry/sphere_intersect.h"
#include "core/sampling/sampler.h"
#include "core/sampling/sampling.h"
#include "core/sampling/unit_circle.h"
#include "core/scene/background.h"
#include "core/scene/camera.h"
#include "materials/material.h"

namespace rtiow {
namespace {

SurfaceHit facing_up() {
  SurfaceHit h{};
  h.normal = {0, 1, 0};
  h.front_face = true;
  return h;
}

TEST(PinnedSky, GradientFollowsTheBooksBlendExactly) {
  const Background sky;  // horizon white, zenith (0.5, 0.7, 1)
  for (const double y : {-1.0, -0.5, 0.0, 0.3, 0.5, 1.0}) {
    const double x = std::sqrt(1.0 - y * y);
    const Color c = sky(Vec3{float(x), float(y), 0.0f});
    const double t = 0.5 * (y + 1.0);
    EXPECT_NEAR(c.x, (1 - t) * 1.0 + t * 0.5, 2e-6) << "y = " << y;
    EXPECT_NEAR(c.y, (1 - t) * 1.0 + t * 0.7, 2e-6) << "y = " << y;
    EXPECT_NEAR(c.z, 1.0, 2e-6) << "y = " << y;
  }
  // Direction length does not matter.
  EXPECT_NEAR(sky(Vec3{0, 5, 0}).x, 0.5f, 1e-6f);
}

TEST(PinnedFresnel, SchlickMatchesItsFormula) {
  for (const double eta : {1.0 / 1.5, 1.5, 1.0 / 2.4}) {
    for (const double c : {1.0, 0.9, 0.7, 0.5, 0.3, 0.1, 0.0}) {
      const double r0 = std::pow((1 - eta) / (1 + eta), 2);
      const double expected = r0 + (1 - r0) * std::pow(1 - c, 5);
      EXPECT_NEAR(schlick_reflectance(float(c), float(eta)), expected, 2e-6)
          << "cos " << c << ", eta " << eta;
    }
  }
}

TEST(PinnedFresnel, ExactMatchesTheFresnelEquations) {
  for (const double eta : {1.0 / 1.5, 1.5}) {
    for (const double c : {1.0, 0.95, 0.8, 0.6, 0.4, 0.2}) {
      const double sin2_t = eta * eta * (1 - c * c);
      double expected = 1.0;  // total internal reflection
      if (sin2_t < 1) {
        const double ct = std::sqrt(1 - sin2_t);
        const double rs = (eta * c - ct) / (eta * c + ct);
        const double rp = (c - eta * ct) / (c + eta * ct);
        expected = 0.5 * (rs * rs + rp * rp);
      }
      EXPECT_NEAR(exact_reflectance(float(c), float(eta)), expected, 2e-6)
          << "cos " << c << ", eta " << eta;
    }
  }
}

// Entering glass at 60 degrees: Schlick gives 0.04 + 0.96 * 0.5^5 = 0.07. The glass must
// reflect that often (binomial, 5 standard deviations: 0.002 of 0.07, so 3% off fails).
TEST(PinnedFresnel, GlassReflectsAsOftenAsSchlickSays) {
  const Material glass = Dielectric{1.5f};
  const Vec3 in{std::sqrt(0.75f), -0.5f, 0.0f};
  const int n = 400000;
  int reflected = 0;
  for (int i = 0; i < n; ++i) {
    const BounceSample u = SampleStream(11, 0, 0, std::uint64_t(i)).next_bounce();
    if (scatter(glass, in, facing_up(), u)->direction.y > 0) ++reflected;
  }
  const double p = 0.04 + 0.96 * std::pow(0.5, 5);
  EXPECT_NEAR(double(reflected) / n, p, 5 * std::sqrt(p * (1 - p) / n));
}

// The warps, against their closed forms in double: z = 1 - 2 u1 and phi = 2 pi u2 on the
// sphere; radius cbrt(u3) in the ball; Shirley and Chiu's concentric map on the disk.
TEST(PinnedWarps, MatchTheirClosedForms) {
  const double pi = 3.14159265358979323846;
  // u in [0, 15/16]: at the sphere's poles sqrt(1 - z^2) is ill-conditioned in float.
  for (int i = 0; i < 16; ++i) {
    for (int j = 0; j < 16; ++j) {
      const double u1 = i / 16.0, u2 = j / 16.0 + 1.0 / 32.0;
      const Vec3 v = sample_unit_vector(float(u1), float(u2));
      const double z = 1 - 2 * u1, r = std::sqrt(std::max(0.0, 1 - z * z));
      EXPECT_NEAR(v.z, z, 1e-6) << u1;
      EXPECT_NEAR(v.x, r * std::cos(2 * pi * u2), 2e-6) << u1 << " " << u2;
      EXPECT_NEAR(v.y, r * std::sin(2 * pi * u2), 2e-6) << u1 << " " << u2;
      const Vec3 b = sample_in_unit_sphere(float(u1), float(u2), float(u2));
      EXPECT_NEAR(length(Vec3d(b)), std::cbrt(u2), 2e-6) << u2;

      const double a = 2 * u1 - 1, c = 2 * u2 - 1;
      double dr = 0, theta = 0;
      if (a == 0 && c == 0) {
      } else if (std::abs(a) > std::abs(c)) {
        dr = a, theta = pi / 4 * (c / a);
      } else {
        dr = c, theta = pi / 2 - pi / 4 * (a / c);
      }
      const Vec3 d = sample_in_unit_disk(float(u1), float(u2));
      EXPECT_NEAR(d.x, dr * std::cos(theta), 2e-6) << u1 << " " << u2;
      EXPECT_NEAR(d.y, dr * std::sin(theta), 2e-6) << u1 << " " << u2;
    }
  }
}

// The warps' inline cos and sin of 2 pi u, against double over the whole turn and beyond
// (the disk passes negative turns): within 3e-7, a few float ulps of 1, at every quarter
// turn's seam and between; and exact at the quarter turns themselves.
TEST(PinnedWarps, CirclePointIsCosAndSinOfTheTurn) {
  const double pi = 3.14159265358979323846;
  double worst = 0;
  for (int i = -(1 << 18); i <= (1 << 18); ++i) {
    const float turns = float(i) / float(1 << 17) + 0x1p-21f;
    const CirclePoint p = circle_point(turns);
    const double angle = 2 * pi * double(turns);
    worst = std::max({worst, std::abs(p.cos - std::cos(angle)), std::abs(p.sin - std::sin(angle))});
  }
  EXPECT_LT(worst, 3e-7);
  for (int k = -4; k <= 4; ++k) {
    const CirclePoint p = circle_point(0.25f * float(k));
    const int q = (k % 4 + 4) % 4;
    EXPECT_EQ(p.cos, q == 0 ? 1.0f : q == 2 ? -1.0f : 0.0f) << k;
    EXPECT_EQ(p.sin, q == 1 ? 1.0f : q == 3 ? -1.0f : 0.0f) << k;
  }
  const CirclePoint nowhere = circle_point(std::numeric_limits<float>::quiet_NaN());
  EXPECT_TRUE(std::isnan(nowhere.cos) && std::isnan(nowhere.sin));
}

// The lens is a disk of diameter `aperture` around lookfrom: a sample at the disk's edge
// starts the ray aperture / 2 from lookfrom, in the film plane's directions.
TEST(PinnedCamera, LensRadiusIsHalfTheAperture) {
  CameraSettings settings;
  settings.lookfrom = {1, 2, 3};
  settings.lookat = {1, 2, -7};
  settings.vfov_degrees = 40;
  settings.aperture = 0.8;
  settings.focus_distance = 10;
  const Camera camera(settings, 64, 48);
  for (const float v : {0.5f, 0.999999f, 0.0f}) {
    const Ray ray = camera.generate_ray(0.3f, 0.6f, v == 0.5f ? 0.999999f : 0.5f, v);
    const Vec3 moved = ray.origin - Vec3(settings.lookfrom);
    EXPECT_NEAR(length(moved), 0.4f, 1e-5f) << v;
    EXPECT_NEAR(moved.z, 0.0f, 1e-6f) << "the lens lies in the film plane";
  }
}

// A fuzzy metal adds fuzz x (a uniform point in the unit ball) to the mirror direction: the
// deviation is at most `fuzz` long and its mean square is 3/5 fuzz^2. With 200k samples the
// mean square is known to 0.15%; a fuzz 1% off moves it 2%.
TEST(PinnedMetal, FuzzBallHasTheStatedRadius) {
  constexpr float kFuzz = 0.5f;
  const Material metal = make_metal({1, 1, 1}, kFuzz);
  const Vec3 in{0, -1, 0};
  const Vec3 mirror{0, 1, 0};
  const int n = 200000;
  double sum_squares = 0, longest = 0;
  for (int i = 0; i < n; ++i) {
    const BounceSample u = SampleStream(12, 0, 0, std::uint64_t(i)).next_bounce();
    const std::optional<Scattered> s = scatter(metal, in, facing_up(), u);
    ASSERT_TRUE(s) << "fuzz 0.5 at normal incidence never goes below the surface";
    const double d = length(Vec3d(s->direction - mirror));
    sum_squares += d * d;
    longest = std::max(longest, d);
  }
  const double expected = 0.6 * kFuzz * kFuzz;
  const double sd = kFuzz * kFuzz * std::sqrt(3.0 / 7.0 - 9.0 / 25.0) / std::sqrt(double(n));
  EXPECT_NEAR(sum_squares / n, expected, 5 * sd);
  EXPECT_LE(longest, kFuzz * (1 + 1e-6));
  EXPECT_GT(longest, kFuzz * 0.99) << "the ball's edge is reached";
}

// A spawned ray starts outside the hit point's error box, and no farther: its distance from
// the point is at most the bound the float computation needs (half an ulp per coordinate,
// summed along the normal) plus the two roundings away from the surface. A loose offset
// leaks light through contacts; a 10x looser one fails here.
TEST(PinnedOffset, SpawnedRaysStartJustOutsideTheErrorBound) {
  Pcg32 rng(5, 6);
  for (const float scale : {1e-3f, 1.0f, 1e3f, 1e6f}) {
    SphereSet spheres;
    spheres.add({0.3f * scale, -0.2f * scale, 1.7f * scale}, 0.9f * scale, 0);
    for (int i = 0; i < 2000; ++i) {
      const Vec3 d = sample_unit_vector(rng.next_float(), rng.next_float());
      const Vec3 origin = spheres.center(0) - 3.0f * scale * d;
      const Ray ray{origin, d};
      const float t = sphere_hit_distance(spheres.center(0), spheres.radius[0], ray, 0.0f,
                                          std::numeric_limits<float>::infinity());
      if (!std::isfinite(t)) continue;
      const SurfaceHit hit = make_surface_hit(spheres, ray, Hit{t, 0});
      const Vec3 out = sample_unit_vector(rng.next_float(), rng.next_float());
      const Ray spawned = spawn_ray(hit, dot(out, hit.normal) > 0 ? out : -out);
      const Vec3 p = abs(hit.point);
      const float eps = std::numeric_limits<float>::epsilon();
      const float needed = 0.5f * eps * (p.x + p.y + p.z);  // the error box along the normal
      for (std::size_t k = 0; k < 3; ++k) {
        const float moved = std::abs(spawned.origin[k] - hit.point[k]);
        EXPECT_LE(moved, 1.01f * needed + 2.0f * eps * p[k] + 1e-30f)
            << "scale " << scale << ", ray " << i << ", axis " << k;
      }
      EXPECT_GT(dot(spawned.origin - hit.point, hit.normal) *
                    (dot(spawned.direction, hit.normal) > 0 ? 1.0f : -1.0f),
                0.0f)
          << "the origin moves to the side the ray leaves to";
    }
  }
}

}  // namespace
}  // namespace rtiow
