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

// A ray from a random point in and around the cover scene, in a random direction.
Ray random_ray(Pcg32& rng) {
  const Vec3 origin{-15 + 30 * rng.next_float(), 0.01f + 4 * rng.next_float(),
                    -15 + 30 * rng.next_float()};
  return Ray{origin, sample_unit_vector(rng.next_float(), rng.next_float())};
}

// Both found nothing, or the same sphere at the same t, bit for bit.
::testing::AssertionResult same_hit(const std::optional<Hit>& a, const std::optional<Hit>& b) {
  if (a.has_value() != b.has_value()) return ::testing::AssertionFailure() << "one missed";
  if (a && (a->sphere != b->sphere || a->t != b->t)) {
    return ::testing::AssertionFailure() << "sphere " << a->sphere << " at " << a->t
                                         << " against sphere " << b->sphere << " at " << b->t;
  }
  return ::testing::AssertionSuccess();
}

// Both accelerators over `spheres` on 20000 random rays: they must agree on every one, bit
// for bit; `check(embree, naive, ray, hit)` sees each ray that hits. Returns how many did.
template <typename Check>
int agree_on_random_rays(const SphereSet& spheres, std::uint64_t seed, Check check) {
  const EmbreeAccel embree(spheres);
  const NaiveAccel naive(spheres);
  Pcg32 rng(seed, 4);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Ray ray = random_ray(rng);
    const std::optional<Hit> a = embree.intersect(ray, kInf);
    EXPECT_TRUE(same_hit(a, naive.intersect(ray, kInf))) << "ray " << i;
    if (!a) continue;
    ++hits;
    check(embree, naive, ray, *a);
  }
  return hits;
}

// Rays from random points in and around the cover scene in random directions: both
// accelerators must report the same sphere at the same t, bit for bit; and the same next
// hit when told to leave out the first one (as a ray leaving a sphere outward does).
TEST(Accelerators, EmbreeAndNaiveFindIdenticalHits) {
  const Scene scene = make_builtin_scene("cover", 1);
  int second_hits = 0;
  const int hits = agree_on_random_rays(
      scene.spheres, 3,
      [&](const EmbreeAccel& embree, const NaiveAccel& naive, const Ray& ray, const Hit& hit) {
        // Closer than the hit, both find nothing.
        EXPECT_FALSE(embree.intersect(ray, hit.t * 0.5f));
        EXPECT_FALSE(naive.intersect(ray, hit.t * 0.5f));
        const std::optional<Hit> next = embree.intersect(ray, kInf, hit.sphere);
        EXPECT_TRUE(same_hit(next, naive.intersect(ray, kInf, hit.sphere)));
        if (!next) return;
        ++second_hits;
        EXPECT_NE(next->sphere, hit.sphere);
        EXPECT_GE(next->t, hit.t);
      });
  EXPECT_GT(hits, 5000);
  EXPECT_GT(second_hits, 1000);
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
  const int hits = agree_on_random_rays(
      spheres, 5, [&](const EmbreeAccel&, const NaiveAccel&, const Ray&, const Hit& hit) {
        EXPECT_LT(hit.sphere, cover.spheres.size());
      });
  EXPECT_GT(hits, 5000);
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
      ASSERT_TRUE(same_hit(packet_hits[k], single)) << packet << " " << k;
      hits += single.has_value();
    }
  }
  EXPECT_GT(hits, 10000);
}

// The benchmark's traversal-only mode finds nothing, even head-on: its rate is Embree's
// traversal and calls alone, never a render's.
TEST(Accelerators, TraversalOnlyEmbreeFindsNoHit) {
  SphereSet spheres;
  spheres.add({0, 0, -5}, 1.0f, 0);
  const EmbreeAccel traversal_only(spheres, EmbreeCallback::Nothing);
  const EmbreeAccel embree(spheres);
  const Ray ray{{0, 0, 0}, {0, 0, -1}};
  EXPECT_TRUE(embree.intersect(ray, kInf).has_value());
  EXPECT_FALSE(traversal_only.intersect(ray, kInf).has_value());
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
