#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "core/accel/accelerator.h"

#include "core/accel/embree_accel.h"
#include "core/accel/naive_accel.h"
#include "core/sampling/rng.h"
#include "core/sampling/sampling.h"
#include "core/scene/builtin_scenes.h"

namespace rtiow {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Rays from random points in and around the cover scene in random directions: both
// accelerators must report the same sphere at the same t, bit for bit.
TEST(Accelerators, EmbreeAndNaiveFindIdenticalHits) {
  const Scene scene = make_builtin_scene("cover", 1);
  const EmbreeAccel embree(scene.spheres);
  const NaiveAccel naive(scene.spheres);
  Pcg32 rng(3, 4);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 origin{-15 + 30 * rng.next_float(), 0.01f + 4 * rng.next_float(),
                      -15 + 30 * rng.next_float()};
    const Ray ray{origin, sample_unit_vector(rng.next_float(), rng.next_float())};
    const std::optional<Hit> a = embree.intersect(ray, kInf);
    const std::optional<Hit> b = naive.intersect(ray, kInf);
    ASSERT_EQ(a.has_value(), b.has_value()) << "ray " << i;
    if (!a) continue;
    ++hits;
    ASSERT_EQ(a->sphere, b->sphere) << "ray " << i;
    ASSERT_EQ(a->t, b->t) << "ray " << i;
    // Closer than the hit, both find nothing.
    EXPECT_FALSE(embree.intersect(ray, a->t * 0.5f)) << "ray " << i;
    EXPECT_FALSE(naive.intersect(ray, a->t * 0.5f)) << "ray " << i;
  }
  EXPECT_GT(hits, 5000);
}

// Coincident spheres (a scene file that lists one twice, with another material): every ray
// hits both at the same t, and both accelerators must name the same one, the lower index,
// whatever order the BVH visits them in.
TEST(Accelerators, CoincidentSpheresResolveToTheLowerIndex) {
  const Scene cover = make_builtin_scene("cover", 1);
  SphereSet spheres;
  for (int copy = 0; copy < 2; ++copy) {
    for (std::size_t i = 0; i < cover.spheres.size(); ++i) {
      spheres.add(cover.spheres.center(i), cover.spheres.radius[i], std::uint32_t(copy));
    }
  }
  const EmbreeAccel embree(spheres);
  const NaiveAccel naive(spheres);
  Pcg32 rng(5, 6);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 origin{-15 + 30 * rng.next_float(), 0.01f + 4 * rng.next_float(),
                      -15 + 30 * rng.next_float()};
    const Ray ray{origin, sample_unit_vector(rng.next_float(), rng.next_float())};
    const std::optional<Hit> a = embree.intersect(ray, kInf);
    const std::optional<Hit> b = naive.intersect(ray, kInf);
    ASSERT_EQ(a.has_value(), b.has_value()) << "ray " << i;
    if (!a) continue;
    ++hits;
    ASSERT_EQ(a->sphere, b->sphere) << "ray " << i;
    ASSERT_LT(a->sphere, cover.spheres.size()) << "ray " << i;
    ASSERT_EQ(a->t, b->t) << "ray " << i;
  }
  EXPECT_GT(hits, 5000);
}

// A ray may leave out one sphere (the one it leaves outward): both accelerators then find
// the closest hit among the others, the same one.
TEST(Accelerators, LeaveOutTheSphereTheyAreToldTo) {
  const Scene scene = make_builtin_scene("cover", 1);
  const EmbreeAccel embree(scene.spheres);
  const NaiveAccel naive(scene.spheres);
  Pcg32 rng(7, 8);
  int second_hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 origin{-15 + 30 * rng.next_float(), 0.01f + 4 * rng.next_float(),
                      -15 + 30 * rng.next_float()};
    const Ray ray{origin, sample_unit_vector(rng.next_float(), rng.next_float())};
    const std::optional<Hit> first = naive.intersect(ray, kInf);
    if (!first) continue;
    const std::optional<Hit> a = embree.intersect(ray, kInf, first->sphere);
    const std::optional<Hit> b = naive.intersect(ray, kInf, first->sphere);
    ASSERT_EQ(a.has_value(), b.has_value()) << "ray " << i;
    if (!a) continue;
    ASSERT_NE(a->sphere, first->sphere) << "ray " << i;
    ASSERT_EQ(a->sphere, b->sphere) << "ray " << i;
    ASSERT_EQ(a->t, b->t) << "ray " << i;
    ASSERT_GE(a->t, first->t) << "ray " << i;
    ++second_hits;
  }
  EXPECT_GT(second_hits, 1000);
}

// Packets of 1 to 8 rays, coherent (a pixel's camera rays) or not: Embree's rtcIntersect8
// finds the hits rtcIntersect1 finds, bit for bit.
TEST(Accelerators, PacketsFindTheHitsOfSingleRays) {
  const Scene scene = make_builtin_scene("cover", 1);
  const EmbreeAccel embree(scene.spheres);
  Pcg32 rng(9, 10);
  int hits = 0;
  for (int packet = 0; packet < 4000; ++packet) {
    const int count = 1 + packet % kRayPacketSize;
    const bool coherent = packet % 2 == 0;
    const Vec3 origin{13.0f, 2.0f, 3.0f};
    Ray rays[kRayPacketSize];
    for (int k = 0; k < count; ++k) {
      const Vec3 target = coherent ? Vec3{float(packet % 40) * 0.1f - 2.0f, 0.5f, 0.0f} +
                                         0.01f * Vec3{rng.next_float(), rng.next_float(), 0.0f}
                                   : Vec3{-15 + 30 * rng.next_float(), 3 * rng.next_float(),
                                          -15 + 30 * rng.next_float()};
      rays[k] = Ray{origin, target - origin};
    }
    std::optional<Hit> packet_hits[kRayPacketSize];
    intersect_packet(embree, rays, count, packet_hits);
    for (int k = 0; k < count; ++k) {
      const std::optional<Hit> single = embree.intersect(rays[k], kInf);
      ASSERT_EQ(packet_hits[k].has_value(), single.has_value()) << packet << " " << k;
      if (!single) continue;
      ++hits;
      ASSERT_EQ(packet_hits[k]->sphere, single->sphere) << packet << " " << k;
      ASSERT_EQ(packet_hits[k]->t, single->t) << packet << " " << k;
    }
  }
  EXPECT_GT(hits, 10000);
}

TEST(Accelerators, RespectTMax) {
  SphereSet spheres;
  spheres.add({0, 0, -5}, 1.0f, 0);
  const EmbreeAccel embree(spheres);
  const NaiveAccel naive(spheres);
  const Ray ray{{0, 0, 0}, {0, 0, -1}};
  const std::optional<Hit> h = embree.intersect(ray, 4.5f);
  ASSERT_TRUE(h);
  EXPECT_FLOAT_EQ(h->t, 4.0f);
  EXPECT_FLOAT_EQ(naive.intersect(ray, 4.5f)->t, 4.0f);
  EXPECT_FALSE(embree.intersect(ray, 3.5f));
  EXPECT_FALSE(naive.intersect(ray, 3.5f));
}

static_assert(Accelerator<EmbreeAccel> && Accelerator<NaiveAccel>);

TEST(Accelerators, EmptySceneHitsNothing) {
  SphereSet spheres;
  const EmbreeAccel embree(spheres);
  EXPECT_FALSE(embree.intersect(Ray{{0, 0, 0}, {1, 0, 0}}, kInf));
}

}  // namespace
}  // namespace rtiow
