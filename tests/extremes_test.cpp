// Numerical robustness at the extremes: scale invariance, a huge ground, the white furnace,
// parameters at their limits, and a sweep of random extreme scenes for NaN and Inf.

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>

#include "core/compare/image_diff.h"
#include "core/geometry/ray_offset.h"
#include "core/geometry/sphere_intersect.h"
#include "core/limits/error.h"
#include "core/render/render.h"
#include "core/sampling/rng.h"
#include "core/scene/builtin_scenes.h"

namespace rtiow {
namespace {

RenderSettings small(const Scene& scene, int width, int spp, int depth, std::uint64_t seed = 5) {
  RenderSettings s;
  s.width = width;
  s.height = std::max(1, int(std::lround(width / scene.image.aspect_ratio)));
  s.samples = FixedSamples{spp};
  s.max_depth = depth;
  s.seed = seed;
  s.sampler = SamplerKind::Independent;
  return s;
}

// Display space, where a user judges the image; the plain comparison only counts pixels
// beyond 0.1 here (the tests assert on the figures).
constexpr PlainThresholds kCounting{0.1, 100.0, 1.0, 0.1, 100.0};

DiffInput display_of(const Film& film) {
  return display_referred(diff_input(film));
}

void expect_finite(const Film& film, const std::string& what) {
  for (const Color& c : film.pixels()) {
    ASSERT_TRUE(is_finite(c)) << what << ": a pixel is NaN or infinite";
    ASSERT_GE(std::min({c.x, c.y, c.z}), 0.0f) << what << ": a pixel is negative";
  }
}

// The whole scene, camera included, scaled about the origin.
Scene scaled(Scene scene, double factor) {
  SphereSet& s = scene.spheres;
  for (std::size_t i = 0; i < s.size(); ++i) {
    s.center_x[i] = float(double(s.center_x[i]) * factor);
    s.center_y[i] = float(double(s.center_y[i]) * factor);
    s.center_z[i] = float(double(s.center_z[i]) * factor);
    s.radius[i] = float(double(s.radius[i]) * factor);
  }
  scene.camera.lookfrom = factor * scene.camera.lookfrom;
  scene.camera.lookat = factor * scene.camera.lookat;
  scene.camera.focus_distance = focus_distance_of(scene.camera) * factor;
  scene.camera.aperture *= factor;
  return scene;
}

// ---- Scale invariance ------------------------------------------------------------------

class ScaleInvariance : public ::testing::TestWithParam<std::string> {};

TEST_P(ScaleInvariance, ScaledScenesRenderTheSameImage) {
  const Scene base = make_builtin_scene(GetParam(), 1);
  const RenderSettings s = small(base, 96, 16, 12);
  const DiffInput reference = display_of(render(base, s).film);
  for (int k = -4; k <= 5; ++k) {
    if (k == 0) continue;
    const Film film = render(scaled(base, std::pow(10.0, k)), s).film;
    expect_finite(film, "scale 1e" + std::to_string(k));
    const PlainDiff d = plain_diff(display_of(film), reference, kCounting);
    std::printf("%s scaled by 1e%d: %s\n", GetParam().c_str(), k, describe(d, kCounting).c_str());
    // Measured: PSNR 72-150 dB, worst pixel 0.021, no pixel beyond 0.1 (display space).
    EXPECT_LT(d.mean_error, 1e-3) << "scale 1e" << k;
    EXPECT_LT(d.max_error, 0.1) << "scale 1e" << k;
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, ScaleInvariance, ::testing::Values("materials", "cover"));

// ---- The huge ground ---------------------------------------------------------------------

Scene cover_with_ground(double radius) {
  Scene scene = make_builtin_scene("cover", 1);
  scene.spheres.center_y[0] = float(-radius);  // the ground is sphere 0; its top stays at y = 0
  scene.spheres.radius[0] = float(radius);
  return scene;
}

// Where primary rays of the cover's camera meet a ground of radius R, against the same
// intersection done wholly in double (ray included): within 1e-5 units for every R.
TEST(HugeGround, HitPointsMatchDoublePrecision) {
  for (double radius : {1e3, 1e4, 1e5, 1e6, 1e7}) {
    const Scene scene = cover_with_ground(radius);
    const Camera camera(scene.camera, 64, 43);
    double worst = 0;
    int hits = 0;
    for (int y = 22; y < 43; ++y) {
      for (int x = 0; x < 64; ++x) {
        const Ray ray =
            camera.generate_ray((float(x) + 0.5f) / 64.0f, (float(y) + 0.5f) / 43.0f, 0.5f, 0.5f);
        const float t = sphere_hit_distance(scene.spheres.center(0), scene.spheres.radius[0], ray,
                                            0.0f, std::numeric_limits<float>::infinity());
        if (!(t < std::numeric_limits<float>::infinity())) continue;
        ++hits;
        const Vec3 p = make_surface_hit(scene.spheres, ray, Hit{t, 0}).point;
        const Rayd exact_ray{Vec3d(ray.origin), Vec3d(ray.direction)};
        const double t_exact = sphere_hit_distance(Vec3d(0, -radius, 0), radius, exact_ray, 0.0,
                                                   std::numeric_limits<double>::infinity());
        worst = std::max(worst, length(Vec3d(p) - exact_ray.at(t_exact)));
      }
    }
    std::printf("ground radius %g: %d hits, worst distance from the double-precision hit %.3g\n",
                radius, hits, worst);
    EXPECT_GT(hits, 500);
    EXPECT_LT(worst, 1e-5) << "ground radius " << radius;
  }
}

// From radius 1e5 on, the ground under the spheres (within ~20 units) is flat to within
// 0.002: renders must agree with one another there, and nothing may sink into the floor or
// turn black. (The horizon itself still dips by sqrt(2h/R): 0.36 degrees at 1e5, a real
// difference, so the top fifth of the frame is left out.)
TEST(HugeGround, RendersAsTheFlatFloor) {
  const RenderSettings s = small(make_builtin_scene("cover", 1), 96, 16, 12);
  auto ground_part = [&](const Film& film) {
    DiffInput below_horizon = display_of(film);
    const int top = s.height / 5;
    below_horizon.rgb.erase(below_horizon.rgb.begin(),
                            below_horizon.rgb.begin() + 3 * std::ptrdiff_t(top) * s.width);
    below_horizon.height -= top;
    return below_horizon;
  };
  const DiffInput flat = ground_part(render(cover_with_ground(1e7), s).film);
  for (double radius : {1e5, 1e6}) {
    const Film film = render(cover_with_ground(radius), s).film;
    expect_finite(film, "ground");
    const PlainDiff d = plain_diff(ground_part(film), flat, kCounting);
    std::printf("ground radius %g against 1e7: %s\n", radius, describe(d, kCounting).c_str());
    EXPECT_LT(d.mean_error, 2e-3) << radius;
    EXPECT_LT(d.fail_percent, 0.5) << radius;
  }
}

// ---- The white furnace -------------------------------------------------------------------

// One sphere of radius 1 at the origin under a uniform white sky, seen from (0, 0, 4).
Scene furnace(const Material& material) {
  Scene scene;
  scene.background = Background{{1, 1, 1}, {1, 1, 1}};
  scene.spheres.add({0, 0, 0}, 1.0f, scene.add_material(material));
  scene.camera.lookfrom = {0, 0, 4};
  scene.camera.lookat = {0, 0, 0};
  scene.camera.vfov_degrees = 40;
  scene.image = ImageSettings{48, 1.0, 64, 50};
  return scene;
}

// Pixels more than 0.5% from the sky.
int dark_pixels(const Film& film) {
  int n = 0;
  for (const Color& c : film.pixels()) {
    n += std::abs(c.x - 1.0f) > 0.005f || std::abs(c.y - 1.0f) > 0.005f ||
         std::abs(c.z - 1.0f) > 0.005f;
  }
  return n;
}

TEST(WhiteFurnace, WhiteDiffuseSphereIsInvisible) {
  const Scene scene = furnace(Lambertian{{1, 1, 1}});
  const Film film = render(scene, small(scene, 48, 64, 50)).film;
  expect_finite(film, "furnace");
  EXPECT_EQ(dark_pixels(film), 0) << "a convex white sphere returns every path to the sky";
}

// Glass absorbs nothing: a path either escapes (radiance exactly 1) or is still bouncing
// at the depth limit (0). So a pixel may fall short at depth 50 only by the share of its
// paths still inside the glass after 50 rays; with the limit at 2000 none may.
TEST(WhiteFurnace, GlassSphereOfAnyIndexIsInvisible) {
  for (float ior : {1.0f, 1.33f, 1.5f, 2.4f, 0.75f, 10.0f, 100.0f}) {
    const Scene scene = furnace(Dielectric{ior});
    const Film at_50 = render(scene, small(scene, 48, 64, 50)).film;
    const Film at_2000 = render(scene, small(scene, 48, 64, 2000)).film;
    expect_finite(at_50, "glass");
    const int short_at_50 = dark_pixels(at_50), short_at_2000 = dark_pixels(at_2000);
    std::printf("glass ior %g: %d of %zu pixels short at depth 50, %d at depth 2000\n", ior,
                short_at_50, at_50.pixels().size(), short_at_2000);
    EXPECT_EQ(short_at_2000, 0) << "ior " << ior;
    for (const Color& c : at_50.pixels()) ASSERT_LE(c.x, 1.0f + 1e-5f) << "glass created energy";
  }
}

// Fuzzy metal absorbs by design: rays perturbed below the surface are lost. Measure it.
TEST(WhiteFurnace, FuzzyMetalLosesEnergyAsDocumented) {
  double previous_loss = -1;
  for (float fuzz : {0.0f, 0.25f, 0.5f, 1.0f}) {
    const Scene scene = furnace(make_metal({1, 1, 1}, fuzz));
    const Film film = render(scene, small(scene, 48, 256, 50)).film;
    expect_finite(film, "metal");
    // Mean over the sphere's disk: it spans 0.71 of the half-height (asin(1/4) against the
    // 20-degree half field of view); stay just inside.
    double sum = 0;
    int n = 0;
    for (int y = 0; y < film.height(); ++y) {
      for (int x = 0; x < film.width(); ++x) {
        const double dx = (x + 0.5) / film.width() - 0.5, dy = (y + 0.5) / film.height() - 0.5;
        if (std::hypot(dx, dy) > 0.34) continue;
        sum += film.at(x, y).x;
        ++n;
      }
    }
    const double loss = 1.0 - sum / n;
    std::printf("metal fuzz %.2f: %.2f%% of the energy lost over the sphere's disk\n", fuzz,
                100.0 * loss);
    if (fuzz == 0.0f) {
      EXPECT_LT(loss, 1e-5) << "polished metal of albedo 1 loses nothing";
    } else {
      EXPECT_GT(loss, previous_loss) << "more fuzz, more loss";
    }
    previous_loss = loss;
  }
}

// ---- Parameters at their limits ---------------------------------------------------------

Scene materials_scene() {
  return make_builtin_scene("materials", 1);
}

void expect_renders(const Scene& scene, RenderSettings s, const std::string& what) {
  try {
    expect_finite(render(scene, s).film, what);
  } catch (const InvalidInput& e) {
    ADD_FAILURE() << what << ": refused: " << e.what();
  }
}

void expect_refused(const Scene& scene, RenderSettings s, const std::string& what) {
  EXPECT_THROW(render(scene, s), InvalidInput) << what;
}

TEST(ParameterExtremes, CameraLimitsRenderOrAreRefused) {
  const Scene base = materials_scene();
  const RenderSettings s = small(base, 32, 4, 10);
  for (double vfov : {1e-3, 0.5, 179.0, 179.99}) {
    Scene scene = base;
    scene.camera.vfov_degrees = vfov;
    expect_renders(scene, s, "vfov " + std::to_string(vfov));
  }
  for (double vfov : {0.0, 180.0, -1.0, 400.0}) {
    Scene scene = base;
    scene.camera.vfov_degrees = vfov;
    expect_refused(scene, s, "vfov " + std::to_string(vfov));
  }
  for (double aperture : {0.0, 1e-6, 1e3, 1e6}) {
    Scene scene = base;
    scene.camera.aperture = aperture;
    expect_renders(scene, s, "aperture " + std::to_string(aperture));
  }
  for (double focus : {1e-6, 1e-3, 1e6}) {
    Scene scene = base;
    scene.camera.aperture = 0.5;
    scene.camera.focus_distance = focus;
    expect_renders(scene, s, "focus distance " + std::to_string(focus));
  }
  Scene inside = base;  // camera inside the centre sphere
  inside.camera.lookfrom = {0, 0, -1};
  inside.camera.lookat = {0, 0, -2};
  expect_renders(inside, s, "camera inside a sphere");
}

TEST(ParameterExtremes, MaterialAndGeometryLimitsRender) {
  const Scene base = materials_scene();
  const RenderSettings s = small(base, 32, 4, 10);
  for (float fuzz : {0.0f, 1.0f, 5.0f}) {  // above 1 acts as 1, as in the book
    Scene scene = base;
    scene.materials[3] = make_metal({0.8f, 0.6f, 0.2f}, fuzz);
    EXPECT_LE(std::get<Metal>(scene.materials[3]).fuzz, 1.0f);
    expect_renders(scene, s, "fuzz " + std::to_string(fuzz));
  }
  for (float ior : {1.0f, 0.5f, 1e-3f, 1e3f, 1e6f}) {
    Scene scene = base;
    scene.materials[2] = Dielectric{ior};
    expect_renders(scene, s, "ior " + std::to_string(ior));
  }
  Scene nested = base;  // overlapping and nested spheres
  const auto m = nested.add_material(Lambertian{{0.5f, 0.5f, 0.5f}});
  nested.spheres.add({0.2f, 0.0f, -1.0f}, 0.4f, m);
  nested.spheres.add({0.0f, 0.0f, -1.0f}, 0.1f, m);
  nested.spheres.add({0.0f, 0.0f, -1.0f}, -0.3f, m);
  expect_renders(nested, s, "nested and overlapping spheres");
  Scene zero = base;
  zero.spheres.radius[1] = 0.0f;
  expect_refused(zero, s, "radius 0");
  Scene nan = base;
  nan.spheres.center_x[1] = std::numeric_limits<float>::quiet_NaN();
  expect_refused(nan, s, "NaN centre");
}

TEST(ParameterExtremes, ImageLimitsRender) {
  const Scene base = materials_scene();
  RenderSettings s = small(base, 32, 4, 10);
  for (int depth : {0, 1}) {
    s.max_depth = depth;
    expect_renders(base, s, "depth " + std::to_string(depth));
  }
  s.max_depth = 10;
  s.samples = FixedSamples{1};
  expect_renders(base, s, "spp 1");
  s.width = 1, s.height = 1;
  expect_renders(base, s, "1x1");
  s.width = 20000, s.height = 1;
  expect_renders(base, s, "20000x1");
  s.width = 1, s.height = 5000;
  expect_renders(base, s, "1x5000");
}

// A glass sphere of index 1 is no interface: the image is the one without it (up to the
// noise of different random paths).
TEST(ParameterExtremes, IndexOneGlassIsInvisible) {
  Scene with = materials_scene();
  with.materials[2] = Dielectric{1.0f};
  Scene without = with;
  without.spheres = SphereSet{};
  for (std::size_t i = 0; i < with.spheres.size(); ++i) {
    if (with.spheres.material[i] != 2) {
      without.spheres.add(with.spheres.center(i), with.spheres.radius[i], with.spheres.material[i]);
    }
  }
  const RenderSettings s = small(with, 96, 256, 20);
  const PlainDiff d =
      plain_diff(display_of(render(with, s).film), display_of(render(without, s).film), kCounting);
  std::printf("index-1 glass against no glass: %s\n", describe(d, kCounting).c_str());
  EXPECT_LT(d.mean_error, 0.01);
  EXPECT_LT(d.fail_percent, 0.5);
}

// Random scenes with every parameter drawn from its extreme range: no pixel may ever be
// NaN or infinite. Scenes the validator refuses (a degenerate camera) are counted.
TEST(ParameterExtremes, RandomExtremeScenesNeverProduceNaN) {
  Pcg32 rng(77, 1);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * rng.next_double(); };
  auto decades = [&](double lo, double hi) { return std::pow(10.0, uniform(lo, hi)); };
  auto sign = [&]() { return rng.next_float() < 0.5f ? -1.0 : 1.0; };
  int rendered = 0, refused = 0;
  for (int trial = 0; trial < 60; ++trial) {
    Scene scene;
    const double scale = decades(-3, 4);
    const int count = 1 + int(rng.next_u32() % 12);
    for (int i = 0; i < count; ++i) {
      Material m;
      switch (rng.next_u32() % 3) {
        case 0:
          m = Lambertian{{float(uniform(0, 1)), rng.next_float() < 0.3f ? 1.0f : 0.0f, 0.5f}};
          break;
        case 1:
          m = make_metal({1, 1, 1}, float(uniform(0, 2)));
          break;
        default:
          m = Dielectric{float(decades(-2, 3))};
      }
      const Vec3 center(Vec3d{sign() * scale * decades(-3, 1), sign() * scale * decades(-3, 1),
                              sign() * scale * decades(-3, 1)});
      scene.spheres.add(center, float(sign() * scale * decades(-3, 1)), scene.add_material(m));
    }
    scene.background = Background{{float(uniform(0, 2)), 1, 1}, {0.5f, 0.7f, float(uniform(0, 4))}};
    scene.camera.lookfrom =
        scale * Vec3d{sign() * decades(-2, 2), sign() * decades(-2, 2), sign() * decades(-2, 2)};
    scene.camera.lookat = rng.next_float() < 0.5 ? Vec3d{0, 0, 0} : Vec3d(scene.spheres.center(0));
    scene.camera.vfov_degrees = uniform(0.01, 179.9);
    scene.camera.aperture = rng.next_float() < 0.5f ? 0.0 : scale * decades(-3, 2);
    scene.camera.focus_distance = scale * decades(-3, 3);
    RenderSettings s;
    s.width = 16, s.height = 12, s.samples = FixedSamples{4}, s.max_depth = 20;
    s.seed = std::uint64_t(trial);
    s.sampler = SamplerKind::Independent;
    try {
      expect_finite(render(scene, s).film, "random scene " + std::to_string(trial));
      ++rendered;
    } catch (const InvalidInput&) {
      ++refused;
    }
  }
  std::printf("random extreme scenes: %d rendered finite, %d refused\n", rendered, refused);
  EXPECT_GT(rendered, 50);
}

}  // namespace
}  // namespace rtiow
