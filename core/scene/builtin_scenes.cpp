#include "core/scene/builtin_scenes.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <numbers>
#include <optional>
#include <vector>

#include "core/limits/error.h"
#include "core/limits/image_size.h"
#include "core/limits/nearest_name.h"
#include "core/limits/setting_name.h"
#include "core/parallel/cancellation.h"
#include "core/parallel/huge_pages.h"
#include "core/parallel/parallel_for_range.h"
#include "core/sampling/rng.h"

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

// The cover's three big spheres (glass, diffuse brown, polished metal) and its camera.
void add_cover_big_spheres_and_camera(Scene& s) {
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
}

// A small sphere's material with the cover's odds, 80% diffuse, 15% metal, 5% glass, by
// `choose` in [0,1), drawing its parameters from `rng` in the book's order.
Material cover_material(float choose, Pcg32& rng) {
  auto uniform = [&rng]() { return rng.next_float(); };
  auto uniform_in = [&](float lo, float hi) { return lo + (hi - lo) * uniform(); };
  if (choose < 0.8f) {
    const Color c1{uniform(), uniform(), uniform()};
    const Color c2{uniform(), uniform(), uniform()};
    return Lambertian{c1 * c2};
  }
  if (choose < 0.95f) {
    const Color albedo{uniform_in(0.5f, 1.0f), uniform_in(0.5f, 1.0f), uniform_in(0.5f, 1.0f)};
    return make_metal(albedo, uniform_in(0.0f, 0.5f));
  }
  return Dielectric{1.5f};
}

// Chapter 13.1: the cover. A 22x22 grid of small spheres (80% diffuse, 15% metal, 5% glass)
// around three big ones, drawn from the scene's own random stream in the book's order.
Scene cover_scene(std::uint64_t scene_seed) {
  Scene s;
  Pcg32 rng(mix64(scene_seed), 0xc0ffee);
  s.spheres.reserve(22 * 22 + 4);
  s.spheres.add({0.0f, -1000.0f, 0.0f}, 1000.0f, s.add_material(Lambertian{{0.5f, 0.5f, 0.5f}}));
  const Vec3 keep_clear{4.0f, 0.2f, 0.0f};
  for (int a = -11; a < 11; ++a) {
    for (int b = -11; b < 11; ++b) {
      const float choose = rng.next_float();
      const float x = float(a) + 0.9f * rng.next_float();
      const float z = float(b) + 0.9f * rng.next_float();
      const Vec3 center{x, 0.2f, z};
      if (length(center - keep_clear) <= 0.9f) continue;
      s.spheres.add(center, 0.2f, s.add_material(cover_material(choose, rng)));
    }
  }
  add_cover_big_spheres_and_camera(s);
  return s;
}

// The scaling family: the cover's ground, big spheres and camera, and exactly N small
// spheres (radius 0.2, one per unit cell, the cover's material mix) filling cells outwards
// from the origin, so density stays the cover's while the field grows as sqrt(N).
// The cells of the field, in rings of growing Chebyshev radius around the origin, leaving out
// those under the three big spheres: the first `count` of them. Ring r is the border of the
// square [-r-1, r]^2, walked by rows of a, then b: its first and last rows whole, the
// others at their two ends.
std::vector<std::array<int, 2>> field_cells(std::uint64_t count) {
  auto blocked = [](int a, int b) { return b >= -2 && b <= 1 && (a >= -6 && a <= 5); };
  std::vector<std::array<int, 2>> cells;
  cells.reserve(count);
  advise_huge_pages(cells);
  const auto take = [&](int a, int b) {
    if (cells.size() < count && !blocked(a, b)) cells.push_back({a, b});
  };
  for (int ring = 0; cells.size() < count; ++ring) {
    if (ring % 256 == 0) throw_if_cancelled();
    for (int a = -ring - 1; a <= ring; ++a) {
      if (a == -ring - 1 || a == ring) {
        for (int b = -ring - 1; b <= ring; ++b) take(a, b);
      } else {
        take(a, -ring - 1);
        take(a, ring);
      }
    }
  }
  return cells;
}

Scene sphere_field_scene(std::uint64_t count, std::uint64_t scene_seed) {
  Scene s;
  s.spheres.add({0.0f, -1000.0f, 0.0f}, 1000.0f, s.add_material(Lambertian{{0.5f, 0.5f, 0.5f}}));
  const std::vector<std::array<int, 2>> cells = field_cells(count);
  // Every sphere draws from its own stream, keyed by its index, so the spheres are made in
  // parallel and the scene is the same for any thread count.
  const std::size_t first = s.spheres.size();
  SphereSet& spheres = s.spheres;
  spheres.reserve(first + count + 3);  // the big three follow
  s.materials.reserve(first + count + 3);
  for (const auto* v : {&spheres.center_x, &spheres.center_y, &spheres.center_z, &spheres.radius})
    advise_huge_pages(*v);
  advise_huge_pages(spheres.material);
  advise_huge_pages(s.materials);
  spheres.center_x.resize(first + count), spheres.center_y.resize(first + count);
  spheres.center_z.resize(first + count), spheres.radius.resize(first + count);
  spheres.material.resize(first + count);
  s.materials.resize(first + count);
  const std::uint64_t stream = mix64(scene_seed);
  parallel_for_range(count, 4096, [&](std::size_t begin, std::size_t end) {
    if (cancellation_requested()) return;  // the rest is skipped, and the scene thrown away
    for (std::size_t k = begin; k < end; ++k) {
      Pcg32 rng(stream, hash_combine(0xf1e1d, k));
      const float choose = rng.next_float();
      const auto [a, b] = cells[k];
      const std::size_t i = first + k;
      spheres.center_x[i] = float(a) + 0.1f + 0.8f * rng.next_float();
      spheres.center_y[i] = 0.2f;
      spheres.center_z[i] = float(b) + 0.1f + 0.8f * rng.next_float();
      spheres.radius[i] = 0.2f;
      spheres.material[i] = std::uint32_t(i);
      s.materials[i] = cover_material(choose, rng);
    }
  });
  throw_if_cancelled();
  add_cover_big_spheres_and_camera(s);
  return s;
}

struct Entry {
  BuiltinScene info;
  Scene (*make)(std::uint64_t scene_seed);
  bool random_layout = false;
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
       cover_scene,
       true},
  };
  return entries;
}

constexpr const char* kFieldPrefix = "spheres:";
constexpr std::uint64_t kMaxFieldSpheres = 100'000'000;

// N of "spheres:N", or nothing when `name` is not of that form; throws when N is bad.
std::optional<std::uint64_t> sphere_field_count(const std::string& name) {
  if (name.rfind(kFieldPrefix, 0) != 0) return std::nullopt;
  const std::string digits = name.substr(std::strlen(kFieldPrefix));
  std::uint64_t n = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
  if (digits.empty() || error != std::errc() || end != digits.data() + digits.size() || n < 1 ||
      n > kMaxFieldSpheres) {
    throw InvalidInput("scene '" + name + "': N must be a whole number from 1 to " +
                       std::to_string(kMaxFieldSpheres));
  }
  // Refused before it is built, as an image too large is: the scene and its BVH take about
  // 190 bytes a sphere at their peak (measured: spheres:4000000 peaks at 733 MB, 1000000 at
  // 165 MB), and may take half of this machine's memory.
  constexpr std::uint64_t kBytesPerSphere = 200;
  const std::uint64_t available = physical_memory_bytes();
  if (n * kBytesPerSphere > available / 2) {
    throw InvalidInput("scene '" + name + "': " + std::to_string(n) + " spheres need about " +
                       std::to_string((n * kBytesPerSphere) >> 20) +
                       " MiB with their BVH, more than half of this machine's " +
                       std::to_string(available >> 20) + " MiB");
  }
  return n;
}

}  // namespace

const std::vector<BuiltinScene>& builtin_scenes() {
  static const std::vector<BuiltinScene> infos = [] {
    std::vector<BuiltinScene> v;
    for (const auto& e : registry()) v.push_back(e.info);
    v.push_back(
        {"spheres:N", "N small spheres on the cover's ground, for scaling (e.g. spheres:100000)"});
    return v;
  }();
  return infos;
}

bool is_builtin_scene_name(const std::string& name) {
  if (name.rfind(kFieldPrefix, 0) == 0) return true;
  return std::any_of(registry().begin(), registry().end(),
                     [&](const auto& e) { return e.info.name == name; });
}

Scene make_builtin_scene(const std::string& name, std::uint64_t scene_seed) {
  if (const auto count = sphere_field_count(name)) {
    Scene s = sphere_field_scene(*count, scene_seed);
    s.name = name;
    s.layout_seed = scene_seed;
    return s;
  }
  for (const auto& e : registry()) {
    if (e.info.name == name) {
      Scene s = e.make(scene_seed);
      s.name = name;
      if (e.random_layout) s.layout_seed = scene_seed;
      return s;
    }
  }
  std::string known;
  std::vector<std::string> names;
  for (const auto& e : registry()) known += e.info.name + ", ", names.push_back(e.info.name);
  // `--scene base.json`: a scene file is given by its path alone.
  const bool looks_like_a_file =
      name.find('/') != std::string::npos || name.ends_with(".json") || name == "-";
  throw InvalidInput(
      "unknown scene " + quote_value(name) + did_you_mean(name, names) + " (known: " + known +
      kFieldPrefix + "N with N from 1 to " + std::to_string(kMaxFieldSpheres) + ")" +
      (looks_like_a_file ? "; a scene file is given by its path, without " + setting("scene")
                         : std::string()));
}

}  // namespace rtiow
