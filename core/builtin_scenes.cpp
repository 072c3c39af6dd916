#include "core/builtin_scenes.h"

#include <cmath>
#include <numbers>

#include "core/error.h"
#include "core/rng.h"

namespace rtiow {
namespace {

// Chapter 10.5: ground, diffuse centre, hollow glass left (outer r=0.5, inner r=-0.4),
// polished metal right. The book's camera of that chapter is a 90-degree pinhole at the
// origin looking down -z.
Scene material_scene() {
  Scene s;
  const auto ground = s.add_material(Lambertian{{0.8f, 0.8f, 0.0f}});
  const auto center = s.add_material(Lambertian{{0.1f, 0.2f, 0.5f}});
  const auto glass = s.add_material(Dielectric{1.5f});
  const auto metal = s.add_material(make_metal({0.8f, 0.6f, 0.2f}, 0.0f));
  s.spheres.add({0.0f, -100.5f, -1.0f}, 100.0f, ground);
  s.spheres.add({0.0f, 0.0f, -1.0f}, 0.5f, center);
  s.spheres.add({-1.0f, 0.0f, -1.0f}, 0.5f, glass);
  s.spheres.add({-1.0f, 0.0f, -1.0f}, -0.4f, glass);
  s.spheres.add({1.0f, 0.0f, -1.0f}, 0.5f, metal);
  s.camera = CameraSettings{};
  s.image = ImageSettings{400, 16.0 / 9.0, 100, 50};
  return s;
}

// Chapter 11.1: two touching spheres that just fill a 90-degree field of view.
Scene wide_angle_scene() {
  Scene s;
  const float r = std::cos(std::numbers::pi_v<float> / 4.0f);
  const auto blue = s.add_material(Lambertian{{0.0f, 0.0f, 1.0f}});
  const auto red = s.add_material(Lambertian{{1.0f, 0.0f, 0.0f}});
  s.spheres.add({-r, 0.0f, -1.0f}, r, blue);
  s.spheres.add({r, 0.0f, -1.0f}, r, red);
  s.camera = CameraSettings{};
  s.image = ImageSettings{400, 16.0 / 9.0, 100, 50};
  return s;
}

// Chapter 11.2: the material scene from (-2,2,1), at vfov 90 and zoomed in at vfov 20.
Scene viewpoint_scene(double vfov) {
  Scene s = material_scene();
  s.camera.lookfrom = {-2, 2, 1};
  s.camera.lookat = {0, 0, -1};
  s.camera.vfov_degrees = vfov;
  return s;
}

// Chapter 12.2: the viewpoint scene at vfov 20 with a wide aperture, focused on the centre
// sphere.
Scene defocus_scene() {
  Scene s = viewpoint_scene(20.0);
  s.camera.lookfrom = {3, 3, 2};
  s.camera.aperture = 2.0;
  s.camera.focus_distance = length(s.camera.lookfrom - s.camera.lookat);
  return s;
}

// Chapter 13.1: the cover. A 22x22 grid of small spheres (80% diffuse, 15% metal, 5% glass)
// around three big ones, drawn from the scene's own random stream in the book's order.
Scene cover_scene(std::uint64_t scene_seed) {
  Scene s;
  Pcg32 rng(mix64(scene_seed), 0xc0ffee);
  auto uniform = [&rng]() { return rng.next_float(); };
  auto uniform_in = [&](float lo, float hi) { return lo + (hi - lo) * uniform(); };

  s.spheres.reserve(22 * 22 + 4);
  s.spheres.add({0.0f, -1000.0f, 0.0f}, 1000.0f, s.add_material(Lambertian{{0.5f, 0.5f, 0.5f}}));
  const Vec3 keep_clear{4.0f, 0.2f, 0.0f};
  for (int a = -11; a < 11; ++a) {
    for (int b = -11; b < 11; ++b) {
      const float choose_material = uniform();
      const float x = float(a) + 0.9f * uniform();
      const float z = float(b) + 0.9f * uniform();
      const Vec3 center{x, 0.2f, z};
      if (length(center - keep_clear) <= 0.9f) continue;
      Material m;
      if (choose_material < 0.8f) {
        const Color c1{uniform(), uniform(), uniform()};
        const Color c2{uniform(), uniform(), uniform()};
        m = Lambertian{c1 * c2};
      } else if (choose_material < 0.95f) {
        const Color albedo{uniform_in(0.5f, 1.0f), uniform_in(0.5f, 1.0f),
                           uniform_in(0.5f, 1.0f)};
        m = make_metal(albedo, uniform_in(0.0f, 0.5f));
      } else {
        m = Dielectric{1.5f};
      }
      s.spheres.add(center, 0.2f, s.add_material(m));
    }
  }
  s.spheres.add({0.0f, 1.0f, 0.0f}, 1.0f, s.add_material(Dielectric{1.5f}));
  s.spheres.add({-4.0f, 1.0f, 0.0f}, 1.0f, s.add_material(Lambertian{{0.4f, 0.2f, 0.1f}}));
  s.spheres.add({4.0f, 1.0f, 0.0f}, 1.0f, s.add_material(make_metal({0.7f, 0.6f, 0.5f}, 0.0f)));

  s.camera.lookfrom = {13, 2, 3};
  s.camera.lookat = {0, 0, 0};
  s.camera.vup = {0, 1, 0};
  s.camera.vfov_degrees = 20.0;
  s.camera.aperture = 0.1;
  s.camera.focus_distance = 10.0;
  s.image = ImageSettings{1200, 3.0 / 2.0, 500, 50};
  return s;
}

struct Entry {
  BuiltinScene info;
  Scene (*make)(std::uint64_t scene_seed);
};

const std::vector<Entry>& registry() {
  static const std::vector<Entry> entries = {
      {{"materials", "ch. 10.5: diffuse, hollow glass and metal spheres on a ground sphere"},
       [](std::uint64_t) { return material_scene(); }},
      {{"wide-angle", "ch. 11.1: two touching spheres (R = cos(pi/4)) filling a 90-degree view"},
       [](std::uint64_t) { return wide_angle_scene(); }},
      {{"viewpoint", "ch. 11.2: the material scene seen from (-2,2,1) with vfov 90"},
       [](std::uint64_t) { return viewpoint_scene(90.0); }},
      {{"viewpoint-zoom", "ch. 11.2: the same viewpoint zoomed in to vfov 20"},
       [](std::uint64_t) { return viewpoint_scene(20.0); }},
      {{"defocus", "ch. 12.2: depth of field from (3,3,2), aperture 2, focused on the centre"},
       [](std::uint64_t) { return defocus_scene(); }},
      {{"cover", "ch. 13.1: the cover, ~480 random small spheres and three big ones (default)"},
       cover_scene},
  };
  return entries;
}

}  // namespace

const std::vector<BuiltinScene>& builtin_scenes() {
  static const std::vector<BuiltinScene> infos = [] {
    std::vector<BuiltinScene> v;
    for (const auto& e : registry()) v.push_back(e.info);
    return v;
  }();
  return infos;
}

Scene make_builtin_scene(const std::string& name, std::uint64_t scene_seed) {
  for (const auto& e : registry()) {
    if (e.info.name == name) {
      Scene s = e.make(scene_seed);
      s.name = name;
      return s;
    }
  }
  std::string known;
  for (const auto& e : registry()) known += (known.empty() ? "" : ", ") + e.info.name;
  throw InvalidInput("unknown scene '" + name + "' (known: " + known + ")");
}

}  // namespace rtiow
