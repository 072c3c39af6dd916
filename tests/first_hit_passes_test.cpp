// The albedo, normal and depth passes (--passes) against geometry whose values are known, and
// their determinism: the same sums for any thread count, either accelerator, any split of the
// samples and any crop, and a beauty image the passes never change.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/limits/error.h"
#include "core/render/first_hit_passes.h"
#include "core/render/render.h"
#include "core/render/render_statistics.h"
#include "core/scene/builtin_scenes.h"
#include "core/scene/camera.h"
#include "tests/film_equality.h"

namespace rtiow {
namespace {

constexpr FirstHitPasses kAll{true, true, true};

// One sphere in front of a pinhole camera at the origin looking down -z: a diffuse ball of a
// known colour at a known place.
Scene ball(const Vec3& center, float radius, const Material& material) {
  Scene scene;
  scene.name = "ball";
  scene.spheres.add(center, radius, scene.add_material(material));
  scene.camera.lookfrom = {0, 0, 0};
  scene.camera.lookat = {0, 0, -1};
  scene.camera.vfov_degrees = 40.0;
  return scene;
}

RenderSettings small(int width, int height, int spp) {
  RenderSettings s;
  s.width = width;
  s.height = height;
  s.samples = FixedSamples{spp};
  s.max_depth = 8;
  s.seed = 3;
  s.sampler = SamplerKind::Independent;
  s.passes = kAll;
  return s;
}

// The pass values of pixel p: albedo, normal, depth.
struct PassValues {
  Color albedo;
  Vec3 normal;
  float depth;
};

PassValues values_at(const RenderResult& r, std::size_t p) {
  const FirstHitSum& sum = r.sums.first_hits[p];
  const std::uint64_t n = r.pixel_samples[p];
  return {{sum.mean(0, n), sum.mean(1, n), sum.mean(2, n)},
          {sum.mean(3, n), sum.mean(4, n), sum.mean(5, n)},
          sum.mean(6, n)};
}

// Where a ray from the origin along `direction` meets the sphere first, in double: the
// distance and the outward unit normal there; nothing when it misses.
struct Analytic {
  double distance;
  Vec3d normal;
};

std::optional<Analytic> hit_sphere(const Vec3d& direction, const Vec3d& center, double radius) {
  const Vec3d d = direction / length(direction);
  const double b = dot(d, center);
  const double c = dot(center, center) - radius * radius;
  const double disc = b * b - c;
  if (disc < 0) return std::nullopt;
  const double t = b - std::sqrt(disc);
  if (t <= 0) return std::nullopt;
  return Analytic{t, (d * t - center) / radius};
}

// From a camera outside a ball: where every corner of a pixel sees the ball, its albedo is the
// material's exactly, and its normal and depth lie within what its corners see (the mean over
// the pixel of a smooth quantity); where no corner, centre or edge comes near it, all is 0.
TEST(FirstHitPasses, MatchAKnownBallPixelByPixel) {
  const Vec3 center{0.3f, -0.2f, -5.0f};
  const float radius = 1.0f;
  const Color colour{0.2f, 0.4f, 0.6f};
  const Scene scene = ball(center, radius, Lambertian{colour});
  const RenderSettings s = small(33, 25, 16);
  const RenderResult r = render(scene, s);
  const Camera camera(scene.camera, s.width, s.height);
  const Vec3d c(center);
  int covered = 0, sky = 0;
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      std::vector<std::optional<Analytic>> corners;
      double closest = 1e9;  // the least miss distance of the pixel's rays from the ball
      for (const auto& [dx, dy] :
           {std::pair{0.0f, 0.0f}, std::pair{1.0f, 0.0f}, std::pair{0.0f, 1.0f},
            std::pair{1.0f, 1.0f}, std::pair{0.5f, 0.5f}}) {
        const Ray ray = camera.generate_ray((float(x) + dx) / float(s.width),
                                            (float(y) + dy) / float(s.height), 0.5f, 0.5f);
        const Vec3d d = Vec3d(ray.direction) / length(Vec3d(ray.direction));
        closest = std::min(closest, length(d * dot(d, c) - c) - radius);
        corners.push_back(hit_sphere(Vec3d(ray.direction), c, radius));
      }
      const auto p = std::size_t(y) * std::size_t(s.width) + std::size_t(x);
      const PassValues v = values_at(r, p);
      SCOPED_TRACE("pixel " + std::to_string(x) + "," + std::to_string(y));
      if (std::all_of(corners.begin(), corners.end(),
                      [](const auto& h) { return h.has_value(); })) {
        ++covered;
        EXPECT_EQ(v.albedo.x, colour.x);
        EXPECT_EQ(v.albedo.y, colour.y);
        EXPECT_EQ(v.albedo.z, colour.z);
        double low = 1e9, high = 0;
        for (const auto& h : corners)
          low = std::min(low, h->distance), high = std::max(high, h->distance);
        EXPECT_GE(v.depth, low - 1e-4);
        EXPECT_LE(v.depth, high + 1e-4);
        for (std::size_t k = 0; k < 3; ++k) {
          double lo = 2, hi = -2;
          for (const auto& h : corners)
            lo = std::min(lo, h->normal[k]), hi = std::max(hi, h->normal[k]);
          EXPECT_GE(v.normal[k], lo - 1e-4) << "normal component " << k;
          EXPECT_LE(v.normal[k], hi + 1e-4) << "normal component " << k;
        }
      } else if (closest > 0.05) {  // well clear of the ball: the sky
        ++sky;
        EXPECT_EQ(v.albedo, Color{});
        EXPECT_EQ(v.normal, Vec3{});
        EXPECT_EQ(v.depth, 0.0f);
      }
    }
  }
  EXPECT_GT(covered, 20);  // neither case is vacuous
  EXPECT_GT(sky, 100);
}

// From inside a ball centred on the camera, every camera ray meets it at its radius: the depth
// is the radius in every pixel, and the normal the material shades with faces the camera (it
// points back along the ray, to the centre).
TEST(FirstHitPasses, InsideABallTheDepthIsItsRadiusAndTheNormalFacesTheCamera) {
  const float radius = 7.5f;
  for (const Material& material :
       {Material{Lambertian{Color{0.9f, 0.1f, 0.3f}}},
        Material{Metal{Color{0.5f, 0.6f, 0.7f}, 0.2f}}, Material{Dielectric{1.5f}}}) {
    const Scene scene = ball({0, 0, 0}, radius, material);
    const RenderSettings s = small(16, 12, 9);
    const RenderResult r = render(scene, s);
    const Camera camera(scene.camera, s.width, s.height);
    const Color expected_albedo = albedo(material);
    for (int y = 0; y < s.height; ++y) {
      for (int x = 0; x < s.width; ++x) {
        const PassValues v = values_at(r, std::size_t(y) * std::size_t(s.width) + std::size_t(x));
        SCOPED_TRACE("pixel " + std::to_string(x) + "," + std::to_string(y));
        EXPECT_NEAR(v.depth, radius, 2e-5 * radius);
        EXPECT_EQ(v.albedo, expected_albedo);
        // The mean of unit normals over the pixel: the centre's direction, reversed, within the
        // pixel's angular size.
        const Ray centre = camera.generate_ray((float(x) + 0.5f) / float(s.width),
                                               (float(y) + 0.5f) / float(s.height), 0.5f, 0.5f);
        const Vec3d d = Vec3d(centre.direction) / length(Vec3d(centre.direction));
        for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(v.normal[k], -d[k], 0.03);
      }
    }
  }
  EXPECT_EQ(albedo(Material{Dielectric{1.5f}}), (Color{1, 1, 1}));  // glass absorbs nothing
}

// The passes' sums are exact: the same bits for 1 and 2 threads and the naive intersector, for
// shares of the samples added, and in a crop; and asking for them never changes the image.
TEST(FirstHitPasses, AreTheSameBitsHoweverTheRenderIsMadeAndLeaveTheImageAlone) {
  const Scene scene = make_builtin_scene("defocus", 1);  // a lens: origins on the lens
  RenderSettings s = small(40, 24, 6);
  s.sampler = SamplerKind::Sobol;
  const RenderResult whole = render(scene, s);
  ASSERT_EQ(whole.sums.first_hits.size(), std::size_t(40 * 24));
  RenderSettings plain = s;
  plain.passes = {};
  const RenderResult without = render(scene, plain);
  EXPECT_TRUE(test::bit_identical(whole.film, without.film));
  EXPECT_TRUE(without.sums.first_hits.empty());
  EXPECT_EQ(whole.sums.color, without.sums.color);
  EXPECT_EQ(whole.sums.spreads, without.sums.spreads);

  for (const int threads : {1, 2}) {
    for (const AccelKind accel : {AccelKind::Embree, AccelKind::Naive}) {
      RenderSettings other = s;
      other.threads = threads;
      other.accel = accel;
      EXPECT_EQ(render(scene, other).sums.first_hits, whole.sums.first_hits)
          << threads << " threads, " << to_string(accel);
    }
  }
  // Samples [0, 4) and [4, 6), added.
  RenderSettings first = s, second = s;
  first.samples = FixedSamples{4};
  second.first_sample = 4;
  second.samples = FixedSamples{2};
  std::vector<FirstHitSum> added = render(scene, first).sums.first_hits;
  const std::vector<FirstHitSum> rest = render(scene, second).sums.first_hits;
  for (std::size_t p = 0; p < added.size(); ++p) added[p] += rest[p];
  EXPECT_EQ(added, whole.sums.first_hits);
  // A crop: the whole render's sums in its region.
  RenderSettings cropped = s;
  cropped.crop = PixelRegion{7, 3, 29, 20};
  const RenderResult crop = render(scene, cropped);
  for (int y = 3; y < 20; ++y) {
    for (int x = 7; x < 29; ++x) {
      EXPECT_EQ(crop.sums.first_hits[std::size_t((y - 3) * 22 + (x - 7))],
                whole.sums.first_hits[std::size_t(y * 40 + x)]);
    }
  }
  // An adaptive render keeps them too, each pixel averaged over its own count.
  RenderSettings adaptive = s;
  adaptive.samples = PixelErrorTarget{0.2, 64};
  const RenderResult a = render(scene, adaptive);
  ASSERT_EQ(a.sums.first_hits.size(), a.pixel_samples.size());
  const std::vector<ExtraChannel> channels = pass_channels(a, kAll);
  ASSERT_EQ(channels.size(), 7u);
  for (const ExtraChannel& c : channels) {
    for (const float v : c.values) EXPECT_TRUE(std::isfinite(v)) << c.name;
  }
}

TEST(FirstHitPasses, ParseTheirNamesAndRefuseOthersByName) {
  EXPECT_EQ(parse_passes("albedo,normal,depth"), kAll);
  EXPECT_EQ(parse_passes("depth"), (FirstHitPasses{false, false, true}));
  EXPECT_EQ(parse_passes("none"), FirstHitPasses{});
  EXPECT_EQ(to_string(parse_passes("depth,albedo")), "albedo,depth");
  EXPECT_EQ(to_string(FirstHitPasses{}), "none");
  try {
    parse_passes("albedo,normals");
    ADD_FAILURE() << "accepted 'normals'";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("unknown pass 'normals'; did you mean normal?"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(parse_passes("depth,depth"), InvalidInput);
  EXPECT_THROW(parse_passes(""), InvalidInput);
  EXPECT_THROW(parse_passes("albedo,"), InvalidInput);
}

TEST(FirstHitPasses, ChannelsCarryCompositorsNames) {
  const Scene scene = ball({0, 0, -4}, 1.0f, Lambertian{Color{0.5f, 0.5f, 0.5f}});
  const RenderResult r = render(scene, small(8, 6, 2));
  std::vector<std::string> names;
  for (const ExtraChannel& c : pass_channels(r, kAll)) names.push_back(c.name);
  EXPECT_EQ(names, (std::vector<std::string>{"albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y",
                                             "N.Z", "Z"}));
  names.clear();
  for (const ExtraChannel& c : pass_channels(r, {false, false, true})) names.push_back(c.name);
  EXPECT_EQ(names, std::vector<std::string>{"Z"});
}

}  // namespace
}  // namespace rtiow
