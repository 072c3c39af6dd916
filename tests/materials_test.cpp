#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/limits/error.h"
#include "core/sampling/sampler.h"
#include "core/scene/scene.h"
#include "core/scene_file/scene_file.h"
#include "materials/material.h"

namespace rtiow {
namespace {

SurfaceHit hit_facing_up(bool front_face) {
  SurfaceHit h{};
  h.point = {0, 0, 0};
  h.normal = {0, 1, 0};
  h.front_face = front_face;
  return h;
}

TEST(Fresnel, SchlickAtNormalIncidenceIsR0) {
  for (float n : {1.0f, 1.33f, 1.5f, 2.4f}) {
    const float r0 = ((1 - n) / (1 + n)) * ((1 - n) / (1 + n));
    EXPECT_FLOAT_EQ(schlick_reflectance(1.0f, n), r0);
    EXPECT_FLOAT_EQ(schlick_reflectance(1.0f, 1.0f / n), r0) << "R0 is symmetric in eta";
  }
  EXPECT_NEAR(schlick_reflectance(1.0f, 1.5f), 0.04f, 1e-6f);
  EXPECT_FLOAT_EQ(schlick_reflectance(0.0f, 1.5f), 1.0f) << "grazing incidence reflects fully";
}

TEST(Fresnel, ExactMatchesKnownValues) {
  // Glass n = 1.5 from air: 0.04 at normal incidence; at 45 degrees Rs = 0.0920, Rp = 0.00847.
  EXPECT_NEAR(exact_reflectance(1.0f, 1.0f / 1.5f), 0.04f, 1e-6f);
  const float cos45 = std::sqrt(0.5f);
  EXPECT_NEAR(exact_reflectance(cos45, 1.0f / 1.5f), 0.5f * (0.092013f + 0.0084663f), 2e-5f);
  EXPECT_NEAR(exact_reflectance(0.0f, 1.0f / 1.5f), 1.0f, 1e-6f) << "grazing reflects fully";
  // Going out of glass past the critical angle asin(1/1.5) = 41.81 degrees: total reflection.
  const float past = std::cos(42.0f * 3.14159265f / 180.0f);
  const float before = std::cos(41.5f * 3.14159265f / 180.0f);
  EXPECT_EQ(exact_reflectance(past, 1.5f), 1.0f);
  EXPECT_LT(exact_reflectance(before, 1.5f), 1.0f);
  EXPECT_NEAR(exact_reflectance(1.0f, 1.5f), 0.04f, 1e-6f) << "normal incidence is symmetric";
  EXPECT_EQ(exact_reflectance(0.7f, 1.0f), 0.0f) << "index 1: no interface";
}

// Schlick's error against exact Fresnel for glass (n = 1.5) over all angles, entering and
// leaving, measured: at most 0.0357 entering (near grazing); leaving, just below the
// critical angle, Schlick (which knows no critical angle) is off by up to 0.616.
TEST(Fresnel, SchlickErrorIsBoundedAsMeasured) {
  float worst_in = 0, worst_out = 0;
  for (int i = 0; i <= 1000; ++i) {
    const float c = float(i) / 1000.0f;
    worst_in = std::max(
        worst_in, std::abs(schlick_reflectance(c, 1 / 1.5f) - exact_reflectance(c, 1 / 1.5f)));
    // Leaving glass, below the critical angle (cos > cos(41.8 degrees) = 0.745).
    if (c > 0.746f) {
      worst_out =
          std::max(worst_out, std::abs(schlick_reflectance(c, 1.5f) - exact_reflectance(c, 1.5f)));
    }
  }
  std::printf("Schlick vs exact, n = 1.5: worst error entering %.4f, leaving %.4f\n", worst_in,
              worst_out);
  EXPECT_LT(worst_in, 0.036f);
  EXPECT_LT(worst_out, 0.62f);
}

// The uniforms of bounce `i` of an independent stream: for the statistical tests.
BounceSample random_bounce(std::uint64_t seed, std::uint64_t i) {
  return SampleStream(seed, 0, 0, i).next_bounce();
}

BounceSample given(float lobe, float u1, float u2, float radius) {
  BounceSample b;
  b.lobe = lobe, b.direction[0] = u1, b.direction[1] = u2, b.radius = radius;
  return b;
}

void expect_direction(const std::optional<Scattered>& s, Vec3 expected, const char* what) {
  ASSERT_TRUE(s) << what;
  EXPECT_NEAR(s->direction.x, expected.x, 1e-6f) << what;
  EXPECT_NEAR(s->direction.y, expected.y, 1e-6f) << what;
  EXPECT_NEAR(s->direction.z, expected.z, 1e-6f) << what;
}

// Given uniforms in, one direction out: the materials are exact functions of their
// BounceSample, so each branch is pinned without statistics.
TEST(ScatterOnGivenUniforms, GlassReflectsBelowTheFresnelReflectanceAndRefractsAbove) {
  const Material glass = Dielectric{1.5f};
  const Vec3 down{0, -1, 0};  // normal incidence: Schlick's reflectance is 0.04
  expect_direction(scatter(glass, down, hit_facing_up(true), given(0.039f, 0.3f, 0.3f, 0.3f)),
                   {0, 1, 0}, "lobe 0.039 < 0.04 reflects");
  expect_direction(scatter(glass, down, hit_facing_up(true), given(0.041f, 0.3f, 0.3f, 0.3f)),
                   {0, -1, 0}, "lobe 0.041 refracts straight through");
  // Entering at 45 degrees: Snell's law, sin t = sin 45 / 1.5.
  const float s45 = std::sqrt(0.5f), sin_t = s45 / 1.5f;
  expect_direction(
      scatter(glass, Vec3{s45, -s45, 0}, hit_facing_up(true), given(0.99f, 0.0f, 0.0f, 0.0f)),
      {sin_t, -std::sqrt(1 - sin_t * sin_t), 0}, "refraction obeys Snell's law");
}

TEST(ScatterOnGivenUniforms, GlassReflectsTotallyPastTheCriticalAngleForAnyLobe) {
  // From inside glass (n = 1.5) the critical angle is asin(1/1.5) = 41.8 degrees.
  const Material glass = Dielectric{1.5f};
  const float theta = 60.0f * 3.14159265f / 180.0f;
  const Vec3 in{std::sin(theta), -std::cos(theta), 0};
  for (const float lobe : {0.0f, 0.5f, 0.99999994f}) {
    const std::optional<Scattered> s =
        scatter(glass, in, hit_facing_up(false), given(lobe, 0.5f, 0.5f, 0.5f));
    expect_direction(s, {in.x, -in.y, 0}, "total internal reflection");
    EXPECT_EQ(s->attenuation, (Color{1, 1, 1}));
  }
}

TEST(ScatterOnGivenUniforms, LambertianIsTheNormalPlusTheUnitVectorOfTheDirectionPair) {
  const Material diffuse = Lambertian{{0.5f, 0.25f, 1.0f}};
  // u = (0.25, 0): z = 1 - 2 u1 = 0.5, phi = 0, so the unit vector is (sqrt(0.75), 0, 0.5).
  for (const float other : {0.0f, 0.7f}) {  // the lobe and radius are not used
    const std::optional<Scattered> s =
        scatter(diffuse, Vec3{0, -1, 0}, hit_facing_up(true), given(other, 0.25f, 0.0f, other));
    expect_direction(s, {std::sqrt(0.75f), 1.0f, 0.5f}, "normal + unit vector");
    EXPECT_EQ(s->attenuation, (Color{0.5f, 0.25f, 1.0f}));
  }
}

TEST(ScatterOnGivenUniforms, FuzzyMetalOffsetsTheMirrorByFuzzTimesTheBallPoint) {
  const Material metal = make_metal({0.9f, 0.8f, 0.7f}, 0.5f);
  // Unit vector (1, 0, 0) (u = (0.5, 0)) at radius cbrt(0.125) = 0.5: offset 0.25 along x.
  expect_direction(
      scatter(metal, Vec3{0, -1, 0}, hit_facing_up(true), given(0.9f, 0.5f, 0.0f, 0.125f)),
      {0.25f, 1.0f, 0.0f}, "mirror + fuzz * ball point");
  // Fuzz 1 pushing a grazing reflection straight down (u = (0.5, 0.75): (0, -1, 0)) absorbs.
  const Material rough = make_metal({1, 1, 1}, 1.0f);
  EXPECT_FALSE(scatter(rough, normalize(Vec3{1, -0.05f, 0}), hit_facing_up(true),
                       given(0.0f, 0.5f, 0.75f, 0.999f)));
}

// A sampler computes only the dimensions a material declares (bounce_uses) and leaves the
// rest 0: so a material must not read any other. Changing the undeclared ones must not
// change what it does.
TEST(ScatterOnGivenUniforms, MaterialsReadOnlyTheDimensionsTheyDeclare) {
  const Material materials[] = {Lambertian{{0.5f, 0.5f, 0.5f}}, make_metal({1, 1, 1}, 0.0f),
                                make_metal({1, 1, 1}, 0.6f), Dielectric{1.5f}};
  const Vec3 in = normalize(Vec3{0.4f, -1.0f, 0.2f});
  for (const Material& m : materials) {
    const unsigned uses = bounce_uses(m);
    for (std::uint64_t i = 0; i < 200; ++i) {
      const BounceSample u = random_bounce(7, i), other = random_bounce(8, i);
      BounceSample mixed = other;  // the declared dimensions from u, the rest from other
      if (uses & kUsesLobe) mixed.lobe = u.lobe;
      if (uses & kUsesDirection)
        mixed.direction[0] = u.direction[0], mixed.direction[1] = u.direction[1];
      if (uses & kUsesRadius) mixed.radius = u.radius;
      for (const bool front : {true, false}) {
        const std::optional<Scattered> a = scatter(m, in, hit_facing_up(front), u),
                                       b = scatter(m, in, hit_facing_up(front), mixed);
        ASSERT_EQ(bool(a), bool(b)) << "material " << m.index();
        if (a) {
          ASSERT_EQ(a->direction, b->direction) << "material " << m.index();
        }
      }
    }
  }
}

TEST(Dielectric, ReflectsWithSchlicksProbability) {
  const Material glass = Dielectric{1.5f};
  const Vec3 in{0, -1, 0};  // normal incidence: reflect with probability 0.04
  int reflected = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    if (scatter(glass, in, hit_facing_up(true), random_bounce(2, std::uint64_t(i)))->direction.y >
        0)
      ++reflected;
  }
  // Binomial(n, 0.04): sd = 62; 5 sd.
  EXPECT_NEAR(reflected, 0.04 * n, 310);
}

TEST(Dielectric, IndexOneIsInvisible) {
  const Material air = Dielectric{1.0f};
  const Vec3 in = normalize(Vec3{0.3f, -1, 0.2f});
  for (const float lobe : {0.0f, 0.5f}) {
    EXPECT_NEAR(length(scatter(air, in, hit_facing_up(true), given(lobe, 0, 0, 0))->direction - in),
                0.0f, 1e-6f);
  }
}

TEST(Metal, PolishedMetalReflectsExactlyWhateverTheUniforms) {
  const Material mirror = make_metal({0.9f, 0.8f, 0.7f}, 0.0f);
  for (const float u : {0.0f, 0.3f, 0.99f}) {
    const std::optional<Scattered> s =
        scatter(mirror, Vec3{1, -1, 0}, hit_facing_up(true), given(u, u, u, u));
    expect_direction(s, normalize(Vec3{1, 1, 0}), "mirror");
    EXPECT_EQ(s->attenuation, (Color{0.9f, 0.8f, 0.7f}));
  }
}

TEST(Metal, FuzzIsClampedToOneAndAbsorbsBelowTheSurface) {
  EXPECT_EQ(make_metal({1, 1, 1}, 3.0f).fuzz, 1.0f);
  const Material rough = make_metal({1, 1, 1}, 1.0f);
  const Vec3 grazing = normalize(Vec3{1, -0.05f, 0});
  int absorbed = 0;
  for (std::uint64_t i = 0; i < 1000; ++i) {
    if (const std::optional<Scattered> s =
            scatter(rough, grazing, hit_facing_up(true), random_bounce(5, i))) {
      EXPECT_GT(dot(s->direction, Vec3{0, 1, 0}), 0.0f) << "only rays above the surface leave";
    } else {
      ++absorbed;
    }
  }
  EXPECT_GT(absorbed, 100) << "fuzz 1 at grazing incidence sends many rays below";
}

TEST(Lambertian, ScattersIntoTheUpperHemisphere) {
  const Material diffuse = Lambertian{{0.5f, 0.5f, 0.5f}};
  double mean_cos = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const std::optional<Scattered> s =
        scatter(diffuse, Vec3{0, -1, 0}, hit_facing_up(true), random_bounce(6, std::uint64_t(i)));
    ASSERT_TRUE(s);
    ASSERT_EQ(s->attenuation, (Color{0.5f, 0.5f, 0.5f})) << "the albedo, exactly";
    const Vec3 out = s->direction;
    ASSERT_TRUE(is_finite(out));
    ASSERT_GE(out.y, 0.0f);
    mean_cos += normalize(out).y;
  }
  // Cosine-distributed directions have E[cos theta] = 2/3; the mean of 20000 has a standard
  // deviation of sqrt(1/18 / 20000) = 0.0017, so 0.005 is 3 of them and a 1% error fails.
  EXPECT_NEAR(mean_cos / n, 2.0 / 3.0, 0.005);
}

// Each material owns its parameter ranges: a scene built in C++ and a scene file are refused
// for the same values, in the same words.
TEST(MaterialParameters, OneRuleForScenesInCppAndInFiles) {
  struct Case {
    Material material;
    std::string file_material, cpp_message, file_message;
  };
  const Case cases[] = {
      {Lambertian{{1.8f, 0.1f, 0.1f}}, R"({"type": "lambertian", "albedo": [1.8, 0.1, 0.1]})",
       "material 0: albedo[0] must be in [0, 1], got 1.8",
       "/materials/m/albedo/0: must be in [0, 1], got 1.8"},
      {Metal{{0.5f, 0.5f, 0.5f}, -0.25f},
       R"({"type": "metal", "albedo": [0.5, 0.5, 0.5], "fuzz": -0.25})",
       "material 0: fuzz must be >= 0 (values above 1 act as 1), got -0.25",
       "/materials/m/fuzz: must be >= 0 (values above 1 act as 1), got -0.25"},
      {Dielectric{0.0f}, R"({"type": "dielectric", "ior": 0})",
       "material 0: ior must be from 0.001 to 1e+06, got 0",
       "/materials/m/ior: must be from 0.001 to 1e+06, got 0"},
  };
  for (const Case& c : cases) {
    Scene scene;
    scene.materials = {c.material};
    scene.spheres.add({0, 0, -2}, 1.0f, 0);
    try {
      validate(scene);
      ADD_FAILURE() << c.cpp_message << ": accepted";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(c.cpp_message), std::string::npos) << e.what();
    }
    const std::string file =
        R"({"version": 1, "camera": {"lookfrom": [0, 0, 0], "lookat": [0, 0, -1], "vfov": 90},
            "image": {"width": 8, "height": 8}, "materials": {"m": )" +
        c.file_material +
        R"(}, "spheres": [{"center": [0, 0, -2], "radius": 1, "material": "m"}]})";
    try {
      parse_scene(file, "m.json");
      ADD_FAILURE() << c.file_message << ": accepted";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(c.file_message), std::string::npos) << e.what();
    }
  }
  // A fuzz above 1 acts as 1 in a file (make_metal clamps) but is refused in a Metal built
  // directly, which would otherwise render a fuzz the comment says cannot happen.
  EXPECT_FALSE(check_parameters(make_metal({0.5f, 0.5f, 0.5f}, 3.0f)));
  EXPECT_TRUE(check_parameters(Metal{{0.5f, 0.5f, 0.5f}, 3.0f}));
}

}  // namespace
}  // namespace rtiow
