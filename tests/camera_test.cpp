#include "core/scene/camera.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "core/limits/error.h"
#include "core/sampling/rng.h"

namespace rtiow {
namespace {

CameraSettings cover_like() {
  CameraSettings c;
  c.lookfrom = {13, 2, 3};
  c.lookat = {0, 0, 0};
  c.vfov_degrees = 20;
  c.focus_distance = 10;
  return c;
}

TEST(Camera, CentrePixelRayPointsAtLookat) {
  const CameraSettings c = cover_like();
  const Camera camera(c, 301, 201);
  const Ray ray = camera.generate_ray(0.5f, 0.5f, 0.0f, 0.0f);
  const Vec3 to_target = normalize(Vec3(c.lookat - c.lookfrom));
  EXPECT_NEAR(dot(normalize(ray.direction), to_target), 1.0f, 1e-6f);
  EXPECT_EQ(ray.origin, Vec3(c.lookfrom));
}

TEST(Camera, FilmCornersSpanTheFieldOfView) {
  CameraSettings c;  // at the origin looking down -z, vfov 90
  const Camera camera(c, 200, 100);
  const Vec3 top = normalize(camera.generate_ray(0.5f, 0.0f, 0, 0).direction);
  const Vec3 bottom = normalize(camera.generate_ray(0.5f, 1.0f, 0, 0).direction);
  EXPECT_NEAR(std::acos(dot(top, bottom)) * 180.0f / 3.14159265f, 90.0f, 1e-3f);
  EXPECT_GT(top.y, 0.0f) << "film t = 0 is the top row";
  const Vec3 right = camera.generate_ray(1.0f, 0.5f, 0, 0).direction;
  EXPECT_GT(right.x, 0.0f) << "film s = 1 is the right edge";
  EXPECT_NEAR(right.x, 2.0f, 1e-5f) << "aspect 2 at focus distance 1";
}

TEST(Camera, LensRaysConvergeOnTheFocusPlane) {
  CameraSettings c = cover_like();
  c.aperture = 2.0;
  const Camera camera(c, 64, 64);
  ASSERT_TRUE(camera.has_lens());
  const Ray pinhole = camera.generate_ray(0.3f, 0.7f, 0.5f, 0.5f);  // the lens centre
  for (float u : {0.0f, 0.25f, 0.9f}) {
    const Ray r = camera.generate_ray(0.3f, 0.7f, u, 1.0f - u);
    EXPECT_GT(length(r.origin - pinhole.origin), 0.0f);
    const Vec3 focus_point = r.at(1.0f), pinhole_focus = pinhole.at(1.0f);
    EXPECT_LT(length(focus_point - pinhole_focus), 1e-4f * length(pinhole_focus));
  }
}

// The render loop makes its camera rays eight at a time; they must be generate_ray's, bit
// for bit, for a lens and a pinhole, at the lens's centre, its edges and its diagonals
// (where the concentric map switches sides) and at random points.
TEST(Camera, RaysMadeEightAtATimeAreGenerateRaysBitForBit) {
  Pcg32 rng(5, 11);
  for (const double aperture : {0.0, 0.1, 3.0}) {
    CameraSettings c = cover_like();
    c.aperture = aperture;
    const Camera camera(c, 400, 225);
    const std::vector<float> special = {0.0f, 0.5f, 1.0f - 0x1p-24f, 0.25f, 0.75f};
    for (int round = 0; round < 200; ++round) {
      Camera::Lanes lanes{};
      for (int k = 0; k < Camera::kLanes; ++k) {
        const bool edge = round < 25;
        lanes.s[k] = rng.next_float(), lanes.t[k] = rng.next_float();
        lanes.lens_u[k] = edge ? special[std::size_t(round % 5)] : rng.next_float();
        lanes.lens_v[k] = edge ? special[std::size_t((round / 5 + k) % 5)] : rng.next_float();
      }
      Ray rays[Camera::kLanes];
      camera.generate_rays(lanes, rays);
      for (int k = 0; k < Camera::kLanes; ++k) {
        const Ray one =
            camera.generate_ray(lanes.s[k], lanes.t[k], lanes.lens_u[k], lanes.lens_v[k]);
        ASSERT_EQ(std::memcmp(&one, &rays[k], sizeof(Ray)), 0)
            << "aperture " << aperture << ", lens (" << lanes.lens_u[k] << ", " << lanes.lens_v[k]
            << ")";
      }
    }
  }
}

void expect_refused(CameraSettings c, const std::string& needle) {
  try {
    validate(c);
    ADD_FAILURE() << "accepted a camera that should be refused (" << needle << ")";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(Camera, RefusesDegenerateSettings) {
  CameraSettings c = cover_like();
  c.lookat = c.lookfrom;
  expect_refused(c, "lookfrom equals lookat");
  c = cover_like();
  c.vup = c.lookat - c.lookfrom;
  expect_refused(c, "vup is parallel");
  c = cover_like();
  c.vup = {0, 0, 0};
  expect_refused(c, "vup is the zero vector");
  for (double vfov : {0.0, -5.0, 180.0, 200.0}) {
    c = cover_like();
    c.vfov_degrees = vfov;
    expect_refused(c, "vfov");
  }
  c = cover_like();
  c.aperture = -1;
  expect_refused(c, "aperture");
  c = cover_like();
  c.focus_distance = 0;
  expect_refused(c, "focus distance");
  c = cover_like();
  c.lookfrom.x = std::numeric_limits<double>::quiet_NaN();
  expect_refused(c, "lookfrom[0] must be finite");
  c = cover_like();
  c.lookat.z = 1e19;  // Embree asserts on rays this far out
  expect_refused(c, "lookat[2] must be finite and within +-1e+15");
  c = cover_like();
  c.focus_distance = 1e-300;
  expect_refused(c, "focus distance must be from 1e-12");
}

TEST(Camera, RefusesRaysBeyondWhatEmbreeTraces) {
  CameraSettings c = cover_like();
  c.vfov_degrees = 179.9999999;
  c.focus_distance = 1e14;
  EXPECT_NO_THROW(validate(c));
  try {
    validate(c, 1 << 20, 1);
    ADD_FAILURE() << "accepted rays of about 1e27";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("its rays reach"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(validate(cover_like(), 1200, 800));
}

TEST(Camera, AcceptsExtremeButValidFieldsOfView) {
  CameraSettings c = cover_like();
  c.vfov_degrees = 1e-3;
  EXPECT_NO_THROW(validate(c));
  c.vfov_degrees = 179.9;
  EXPECT_NO_THROW(validate(c));
}

}  // namespace
}  // namespace rtiow
