// Scene files: every built-in scene survives the round trip to JSON bit for bit, and every
// kind of bad file is refused with one line naming the file, the place and the problem.

#include "core/scene_file/scene_file.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "core/render/render.h"
#include "core/scene/builtin_scenes.h"
#include "tests/film_equality.h"

namespace rtiow {
namespace {

class BuiltinRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(BuiltinRoundTrip, FileRendersTheIdenticalImage) {
  const Scene builtin = make_builtin_scene(GetParam(), 7);
  const std::string text = scene_to_json(builtin);
  const Scene loaded = parse_scene(text, "roundtrip.json");
  EXPECT_EQ(loaded.name, builtin.name);
  EXPECT_EQ(loaded.layout_seed, builtin.layout_seed);
  EXPECT_EQ(loaded.spheres.center_x, builtin.spheres.center_x);
  EXPECT_EQ(loaded.spheres.radius, builtin.spheres.radius);
  EXPECT_EQ(loaded.spheres.material.size(), builtin.spheres.material.size());

  RenderSettings s;
  s.width = 40;
  s.height = std::max(1, int(std::lround(40 / builtin.image.aspect_ratio)));
  s.samples = FixedSamples{3};
  s.max_depth = 10;
  s.seed = 0, s.sampler = SamplerKind::Independent;
  EXPECT_TRUE(test::bit_identical(render(builtin, s).film, render(loaded, s).film));
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, BuiltinRoundTrip,
                         ::testing::Values("materials", "wide-angle", "viewpoint", "viewpoint-zoom",
                                           "defocus", "cover", "spheres:300"),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                           std::string name = param_info.param;
                           for (char& c : name) c = (c == '-' || c == ':') ? '_' : c;
                           return name;
                         });

// A small valid scene; the bad cases below each break one thing in it.
const char* kValid = R"({
  "version": 1,
  "camera": {"lookfrom": [0, 0, 0], "lookat": [0, 0, -1], "vfov": 90},
  "image": {"width": 32, "height": 18, "spp": 4, "depth": 8},
  "materials": {"red": {"type": "lambertian", "albedo": [0.8, 0.1, 0.1]},
                "glass": {"type": "dielectric", "ior": 1.5},
                "steel": {"type": "metal", "albedo": [0.7, 0.7, 0.7], "fuzz": 0.2}},
  "spheres": [{"center": [0, 0, -1], "radius": 0.5, "material": "red"},
              {"center": [0, -100.5, -1], "radius": 100, "material": "steel"},
              {"center": [1, 0, -1], "radius": -0.4, "material": "glass"}]
})";

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the valid scene";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The library's defaults are a scene file's (issue 60): a lens camera with no focus distance,
// built in C++ and read from a file, each rendered with RenderSettings{} (the scene's image
// size and count), gives the same bytes. Before, C++ focused at 1.0 and render() refused a
// width of 0.
TEST(SceneFile, TheLibrarysDefaultsAreTheSceneFiles) {
  const Scene read = parse_scene(R"({
    "version": 1, "name": "lens",
    "camera": {"lookfrom": [0, 1, 3], "lookat": [0, 0, -1], "vfov": 40, "aperture": 0.4},
    "image": {"width": 48, "aspect_ratio": 1.7777777777777777, "spp": 4},
    "materials": {"red": {"type": "lambertian", "albedo": [0.8, 0.1, 0.1]},
                  "steel": {"type": "metal", "albedo": [0.7, 0.7, 0.7], "fuzz": 0.2}},
    "spheres": [{"center": [0, 0, -1], "radius": 0.5, "material": "red"},
                {"center": [0, -100.5, -1], "radius": 100, "material": "steel"}]
  })",
                                 "lens.json");
  Scene built;
  built.name = "lens";
  built.camera.lookfrom = Vec3d{0, 1, 3}, built.camera.lookat = Vec3d{0, 0, -1};
  built.camera.vfov_degrees = 40, built.camera.aperture = 0.4;
  built.image.width = 48, built.image.samples_per_pixel = 4;
  const std::uint32_t red = built.add_material(Lambertian{Color{0.8f, 0.1f, 0.1f}});
  const std::uint32_t steel = built.add_material(Metal{Color{0.7f, 0.7f, 0.7f}, 0.2f});
  built.spheres.add({0.0f, 0.0f, -1.0f}, 0.5f, red);
  built.spheres.add({0.0f, -100.5f, -1.0f}, 100.0f, steel);
  EXPECT_DOUBLE_EQ(focus_distance_of(built.camera), focus_distance_of(read.camera));
  const RenderResult a = render(built, RenderSettings{});
  const RenderResult b = render(read, RenderSettings{});
  EXPECT_EQ(a.film.width(), 48);
  EXPECT_EQ(a.film.height(), 27) << "the side not given follows the scene's aspect ratio";
  EXPECT_EQ(a.samples_completed, 4) << "the scene's count";
  EXPECT_TRUE(test::bit_identical(a.film, b.film));
  // An error target's cap defaults to the command line's (it was 0, refused as "spp > 0").
  RenderSettings by_error;
  by_error.width = 16, by_error.height = 9;
  by_error.samples = ImageErrorTarget{0.5};
  EXPECT_NO_THROW(render(built, by_error));
}

TEST(SceneFile, TheValidSceneLoadsWithItsSettingsAndDefaults) {
  const Scene s = parse_scene(kValid, "dir/valid.json");
  EXPECT_EQ(s.name, "valid") << "the name defaults to the file's stem";
  EXPECT_EQ(s.spheres.size(), 3u);
  EXPECT_EQ(s.materials.size(), 3u);
  EXPECT_EQ(s.image.width, 32);
  EXPECT_DOUBLE_EQ(s.image.aspect_ratio, 32.0 / 18.0);
  EXPECT_EQ(s.camera.vup, (Vec3d{0, 1, 0})) << "vup defaults to +y";
  EXPECT_DOUBLE_EQ(rtiow::focus_distance_of(s.camera), 1.0)
      << "focus defaults to the lookat distance";
  EXPECT_EQ(s.camera.aperture, 0.0);
  EXPECT_EQ(s.spheres.radius[2], -0.4f) << "negative radius: hollow sphere";
}

// JSON has one number type: a whole number written with an exponent is a whole number.
TEST(SceneFile, WholeNumbersMayBeWrittenWithAnExponent) {
  const Scene s = parse_scene(replace(kValid, "\"width\": 32", "\"width\": 3.2e1"), "x.json");
  EXPECT_EQ(s.image.width, 32);
}

TEST(SceneFile, GlassMayAskForExactFresnel) {
  const Scene s = parse_scene(
      replace(kValid, "\"ior\": 1.5}", "\"ior\": 1.5, \"fresnel\": \"exact\"}"), "x.json");
  int glasses = 0;
  for (const Material& m : s.materials) {
    if (const auto* d = std::get_if<Dielectric>(&m)) {
      EXPECT_EQ(d->fresnel, FresnelModel::Exact);
      ++glasses;
    }
  }
  EXPECT_EQ(glasses, 1);
  EXPECT_NE(scene_to_json(s).find("\"fresnel\":\"exact\""), std::string::npos);
  EXPECT_THROW(
      parse_scene(replace(kValid, "\"ior\": 1.5}", "\"ior\": 1.5, \"fresnel\": \"x\"}"), "x.json"),
      InvalidInput);
}

TEST(SceneFile, DefocusAngleSetsTheAperture) {
  const Scene s = parse_scene(
      replace(kValid, "\"vfov\": 90", "\"vfov\": 90, \"defocus_angle\": 10, \"focus_distance\": 3"),
      "x.json");
  EXPECT_NEAR(s.camera.aperture, 2 * 3 * std::tan(5 * 3.14159265358979 / 180), 1e-12);
}

struct BadCase {
  std::string name;
  std::string text;
  std::string message;  // the error must contain this
};

std::vector<BadCase> bad_cases() {
  const std::string v = kValid;
  return {
      {"empty file", "", "line 1, column 1"},
      {"syntax error", replace(v, "\"spp\": 4,", "\"spp\": 4,,"), "line 4, column"},
      {"not an object", "[1, 2]", "/: must be an object"},
      {"no version", replace(v, "\"version\": 1,", ""), "/: missing field \"version\""},
      {"future version", replace(v, "\"version\": 1", "\"version\": 2"),
       "/version: this rtiow reads scene format version 1, got number 2"},
      {"fractional version", replace(v, "\"version\": 1", "\"version\": 1.5"),
       "/version: this rtiow reads scene format version 1, got number 1.5"},
      {"unknown top field", replace(v, "\"version\": 1,", "\"version\": 1, \"lights\": [],"),
       "/lights: unknown field"},
      {"misspelt field", replace(v, "\"vfov\": 90", "\"vfow\": 90"),
       "/camera/vfow: unknown field; did you mean vfov?"},
      {"british spelling", replace(v, "{\"center\": [0, 0, -1]", "{\"centre\": [0, 0, -1]"),
       "/spheres/0/centre: unknown field; did you mean center?"},
      {"missing camera", replace(v, "\"camera\"", "\"kamera\""), "/kamera: unknown field"},
      {"wrong type", replace(v, "\"width\": 32", "\"width\": \"32\""),
       "/image/width: must be a whole number, got string '32'"},
      {"fractional size", replace(v, "\"width\": 32", "\"width\": 32.5"),
       "/image/width: must be a whole number"},
      {"width beyond range as an exponent", replace(v, "\"width\": 32", "\"width\": 1e20"),
       "/image/width: must be from 1 to 1048576, got number 1e+20"},
      {"zero width", replace(v, "\"width\": 32", "\"width\": 0"), "/image/width: must be from 1"},
      {"absurd width", replace(v, "\"width\": 32", "\"width\": 100000000"),
       "/image/width: must be from 1"},
      {"zero spp", replace(v, "\"spp\": 4", "\"spp\": 0"), "/image/spp: must be from 1"},
      {"negative depth", replace(v, "\"depth\": 8", "\"depth\": -1"),
       "/image/depth: must be from 0"},
      {"height and aspect", replace(v, "\"height\": 18", "\"height\": 18, \"aspect_ratio\": 2"),
       "/image: give either \"height\" or \"aspect_ratio\""},
      {"short vector", replace(v, "[0, 0, -1], \"vfov\"", "[0, -1], \"vfov\""),
       "/camera/lookat: must be an array of 3 numbers"},
      {"degenerate camera", replace(v, "\"lookat\": [0, 0, -1]", "\"lookat\": [0, 0, 0]"),
       "/camera: lookfrom equals lookat"},
      {"vfov out of range", replace(v, "\"vfov\": 90", "\"vfov\": 180"),
       "/camera: vfov must lie strictly"},
      {"aperture and angle",
       replace(v, "\"vfov\": 90", "\"vfov\": 90, \"aperture\": 1, \"defocus_angle\": 2"),
       "give either \"aperture\" or \"defocus_angle\""},
      {"negative aperture", replace(v, "\"vfov\": 90", "\"vfov\": 90, \"aperture\": -1"),
       "/camera: aperture must be"},
      {"albedo above 1", replace(v, "[0.8, 0.1, 0.1]", "[1.8, 0.1, 0.1]"),
       "/materials/red/albedo/0: must be in [0, 1], got 1.8"},
      {"negative albedo", replace(v, "[0.8, 0.1, 0.1]", "[0.8, -0.1, 0.1]"),
       "/materials/red/albedo/1: must be in [0, 1]"},
      {"unknown material type", replace(v, "\"type\": \"dielectric\"", "\"type\": \"glass\""),
       "/materials/glass/type: unknown material type 'glass'"},
      {"material field of another type", replace(v, "\"ior\": 1.5", "\"ior\": 1.5, \"fuzz\": 0"),
       "/materials/glass/fuzz: unknown field"},
      {"zero ior", replace(v, "\"ior\": 1.5", "\"ior\": 0"),
       "/materials/glass/ior: must be from 0.001 to 1e+06, got 0"},
      {"negative fuzz", replace(v, "\"fuzz\": 0.2", "\"fuzz\": -0.2"),
       "/materials/steel/fuzz: must be >= 0"},
      {"huge number", replace(v, "\"radius\": 100,", "\"radius\": 1e39,"),
       "/spheres/1/radius: is beyond the limit of +-1e+15"},
      {"overflowing number", replace(v, "\"radius\": 100,", "\"radius\": 1e999,"),
       "line 9, column 53: number overflow parsing '1e999'"},
      {"zero radius", replace(v, "\"radius\": 0.5", "\"radius\": 0"),
       "/spheres/0/radius: must not be 0"},
      {"denormal radius", replace(v, "\"radius\": 0.5", "\"radius\": -1e-39"),
       "/spheres/0/radius: must be at least 1.2e-38 in size"},
      {"unknown material", replace(v, "\"material\": \"red\"", "\"material\": \"blue\""),
       "/spheres/0/material: no material named 'blue'"},
      {"material not a name", replace(v, "\"material\": \"red\"", "\"material\": 3"),
       "/spheres/0/material: must be a material name"},
      {"no spheres", replace(v, "\"spheres\": [", "\"spheres\": [], \"x\": ["),
       "/x: unknown field"},
      {"empty scene",
       std::string(
           R"({"version": 1, "camera": {"lookfrom": [0,0,0], "lookat": [0,0,-1], "vfov": 90},
          "image": {"width": 8, "height": 8}, "materials": {}, "spheres": []})"),
       "/spheres: the scene has no spheres"},
      {"nan literal", replace(v, "\"radius\": 0.5", "\"radius\": NaN"), "line 8, column 48"},
      // Structure: nesting, duplicates, sizes of strings.
      {"deep nesting",
       replace(
           v, "\"version\": 1,",
           "\"version\": 1, \"x\": " + std::string(100000, '[') + std::string(100000, ']') + ","),
       "nested deeper than the limit of 32 levels"},
      {"deep nesting unclosed", std::string(1000000, '['), "nested deeper than the limit"},
      {"duplicate top key", replace(v, "\"version\": 1,", "\"version\": 1, \"version\": 1,"),
       "the key 'version' appears twice in one object"},
      {"duplicate camera key", replace(v, "\"vfov\": 90", "\"vfov\": 90, \"vfov\": 40"),
       "the key 'vfov' appears twice"},
      {"duplicate material", replace(v, "\"steel\":", "\"red\":"),
       "/materials/red: a second material of this name (duplicate key)"},
      {"duplicate sphere key", replace(v, "\"radius\": 0.5", "\"radius\": 0.5, \"radius\": 0.7"),
       "appears twice"},
      {"huge key", replace(v, "\"red\":", "\"" + std::string(100000, 'k') + "\":"),
       "a key of 100000 bytes is longer than the limit of 4096"},
      {"huge string",
       replace(v, "\"material\": \"red\"", "\"material\": \"" + std::string(100000, 'r') + "\""),
       "a string of 100000 bytes is longer than the limit"},
      {"huge array as a value",
       replace(
           v, "\"vfov\": 90",
           "\"vfov\": [" +
               [] {
                 std::string a = "0";
                 for (int i = 0; i < 10000; ++i) a += ",0";
                 return a;
               }() +
               "]"),
       "/camera/vfov: must be a number, got an array of 10001 values"},
      // Numbers the engine cannot trace.
      {"camera far away", replace(v, "\"lookfrom\": [0, 0, 0]", "\"lookfrom\": [1e19, 0, 0]"),
       "/camera/lookfrom/0: is beyond the limit of +-1e+15"},
      {"camera at float infinity",
       replace(v, "\"lookfrom\": [0, 0, 0]", "\"lookfrom\": [0, 1e39, 0]"),
       "/camera/lookfrom/1: is beyond the limit"},
      {"huge focus distance", replace(v, "\"vfov\": 90", "\"vfov\": 90, \"focus_distance\": 1e20"),
       "/camera/focus_distance: is beyond the limit"},
      {"huge aperture", replace(v, "\"vfov\": 90", "\"vfov\": 90, \"aperture\": 1e20"),
       "/camera/aperture: is beyond the limit"},
      {"far sphere", replace(v, "[0, -100.5, -1]", "[0, -1e16, -1]"),
       "/spheres/1/center/1: is beyond the limit"},
      {"huge ior", replace(v, "\"ior\": 1.5", "\"ior\": 1e30"),
       "/materials/glass/ior: must be from"},
      {"aspect ratio too small", replace(v, "\"height\": 18", "\"aspect_ratio\": 1e-300"),
       "/image/aspect_ratio: gives a height of"},
      {"aspect ratio too large", replace(v, "\"height\": 18", "\"aspect_ratio\": 1e300"),
       "/image/aspect_ratio: gives a height of 0 pixels"},
      {"width beyond int64", replace(v, "\"width\": 32", "\"width\": 18446744073709551615"),
       "/image/width: must be from 1 to"},
  };
}

TEST(SceneFile, EveryBadFileGetsOneLineNamingFileAndPlace) {
  for (const BadCase& c : bad_cases()) {
    try {
      parse_scene(c.text, "scenes/bad.json");
      ADD_FAILURE() << c.name << ": accepted";
    } catch (const InvalidInput& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("scenes/bad.json: ", 0), 0u) << c.name << ": " << what;
      EXPECT_NE(what.find(c.message), std::string::npos) << c.name << ": " << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << c.name << ": not one line: " << what;
    }
  }
}

TEST(SceneFile, MissingFileIsNamed) {
  try {
    load_scene_file("/nonexistent/scene.json");
    ADD_FAILURE() << "accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("'/nonexistent/scene.json': No such file"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace rtiow
