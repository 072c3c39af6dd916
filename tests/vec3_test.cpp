#include "core/geometry/vec3.h"

#include <gtest/gtest.h>

namespace rtiow {
namespace {

TEST(Vec3, DotCrossAndLength) {
  const Vec3 x{1, 0, 0}, y{0, 1, 0};
  EXPECT_EQ(dot(x, y), 0.0f);
  EXPECT_EQ(cross(x, y), (Vec3{0, 0, 1}));
  EXPECT_EQ(cross(y, x), (Vec3{0, 0, -1}));
  EXPECT_FLOAT_EQ(length(Vec3{3, 4, 12}), 13.0f);
  EXPECT_FLOAT_EQ(length(normalize(Vec3{-2, 7, 0.5f})), 1.0f);
}

TEST(Vec3, ArithmeticIsComponentwise) {
  const Vec3 a{1, 2, 3}, b{4, 5, 6};
  EXPECT_EQ(a + b, (Vec3{5, 7, 9}));
  EXPECT_EQ(b - a, (Vec3{3, 3, 3}));
  EXPECT_EQ(a * b, (Vec3{4, 10, 18}));
  EXPECT_EQ(2.0f * a, (Vec3{2, 4, 6}));
  EXPECT_EQ(b / 2.0f, (Vec3{2, 2.5f, 3}));
  EXPECT_EQ(-a, (Vec3{-1, -2, -3}));
}

TEST(Vec3, NearZeroAndFinite) {
  EXPECT_TRUE(near_zero(Vec3{1e-9f, -1e-9f, 0}));
  EXPECT_FALSE(near_zero(Vec3{1e-7f, 0, 0}));
  EXPECT_FALSE(is_finite(Vec3{0, std::numeric_limits<float>::infinity(), 0}));
  EXPECT_FALSE(is_finite(Vec3{std::nanf(""), 0, 0}));
}

TEST(Vec3, ReflectMirrorsAboutTheNormal) {
  const Vec3 n{0, 1, 0};
  EXPECT_EQ(reflect(Vec3{1, -1, 0}, n), (Vec3{1, 1, 0}));
  EXPECT_EQ(reflect(Vec3{0, -1, 0}, n), (Vec3{0, 1, 0}));
}

TEST(Vec3, RefractObeysSnellsLaw) {
  const Vec3 n{0, 1, 0};
  for (float degrees : {0.0f, 10.0f, 30.0f, 41.0f}) {
    const float theta = degrees * 3.14159265f / 180.0f;
    const Vec3 in{std::sin(theta), -std::cos(theta), 0};
    const float eta = 1.0f / 1.5f;
    const Vec3 out = refract(in, n, eta);
    EXPECT_NEAR(length(out), 1.0f, 1e-6f);
    EXPECT_LT(out.y, 0.0f) << "refracted ray continues through the surface";
    EXPECT_NEAR(out.x, eta * in.x, 1e-6f) << "sin(out) = eta sin(in) at " << degrees;
  }
}

}  // namespace
}  // namespace rtiow
