// Each material declares its parameters once (materials/material_parameters.h). These tests
// hold the things built from the declarations to them: the scene format's table in the docs,
// the writer (defaults left out, everything else read back exactly) and the reader's refusals.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/limits/error.h"
#include "core/scene_file/material_json.h"
#include "core/scene_file/scene_file.h"

namespace rtiow {
namespace {

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A one-sphere scene file whose only material is `material_json`.
std::string scene_with(const std::string& material_json) {
  return R"({"version": 1, "camera": {"lookfrom": [0, 0, 0], "lookat": [0, 0, -1], "vfov": 90},
            "image": {"width": 8, "height": 8}, "materials": {"m": )" +
         material_json + R"(}, "spheres": [{"center": [0, 0, -2], "radius": 1, "material": "m"}]})";
}

Material read_back(const std::string& material_json) {
  return parse_scene(scene_with(material_json), "m.json").materials.at(0);
}

// docs/scene-format.md shows the table the declarations make, between its two markers.
TEST(MaterialDeclarations, TheSceneFormatTableIsGeneratedFromThem) {
  const std::filesystem::path path =
      std::filesystem::path(RTIOW_SOURCE_DIR) / "docs" / "scene-format.md";
  std::string docs = slurp(path);
  const std::string begin_marker = "<!-- materials: generated from the declarations -->\n";
  const std::string end_marker = "<!-- end of materials -->";
  const std::size_t begin = docs.find(begin_marker);
  const std::size_t end = docs.find(end_marker);
  ASSERT_NE(begin, std::string::npos) << "docs/scene-format.md lost its materials marker";
  ASSERT_NE(end, std::string::npos) << "docs/scene-format.md lost its end-of-materials marker";
  const std::size_t from = begin + begin_marker.size();
  const std::string table = material_format_table();
  if (std::getenv("RTIOW_UPDATE_DOCS")) {
    docs.replace(from, end - from, table);
    std::ofstream(path, std::ios::binary) << docs;
    return;
  }
  EXPECT_EQ(docs.substr(from, end - from), table)
      << "docs/scene-format.md's materials table is stale (RTIOW_UPDATE_DOCS=1 "
         "build/bin/unit_tests --gtest_filter='MaterialDeclarations.*')";
  // Every declared type appears, so a new material cannot be left out of the docs.
  for (const char* type : {"`lambertian`", "`metal`", "`dielectric`"}) {
    EXPECT_NE(table.find(type), std::string::npos) << type;
  }
}

// What the writer leaves out is the default the reader puts back; what it writes reads back
// to the same bits.
TEST(MaterialDeclarations, TheWriterAndTheReaderAgree) {
  const Material materials[] = {
      Lambertian{{0.1f, 0.2f, 0.30000001f}},
      Metal{{0.7903507f, 0.82075393f, 0.7508919f}, 0.15132546f},
      Metal{{0.5f, 0.5f, 0.5f}, 0.0f},
      Dielectric{1.5f},
      Dielectric{1.0f / 1.33f, FresnelModel::Exact},
  };
  for (const Material& m : materials) {
    const std::string json = material_to_json(m);
    const Material back = read_back(json);
    ASSERT_EQ(back.index(), m.index()) << json;
    EXPECT_EQ(material_to_json(back), json);
    visit_material(m, [&](const auto& original) {
      using M = std::decay_t<decltype(original)>;
      const M& read = std::get<M>(back);
      for_each_parameter<M>([&](const auto& d) {
        EXPECT_EQ(read.*d.member, original.*d.member) << json << ": " << d.name;
      });
    });
  }
  // A parameter at its default is left out, and one with no default never is.
  EXPECT_EQ(material_to_json(Metal{{0.5f, 0.5f, 0.5f}, 0.0f}),
            R"({"type":"metal","albedo":[0.5,0.5,0.5]})");
  EXPECT_EQ(material_to_json(Dielectric{1.5f}), R"({"type":"dielectric","ior":1.5})");
}

// Every refusal the reader makes for a parameter is the declaration's own rule.
TEST(MaterialDeclarations, TheReaderRefusesInTheDeclarationsWords) {
  const auto refusal = [](const std::string& material_json) -> std::string {
    try {
      read_back(material_json);
    } catch (const InvalidInput& e) {
      return e.what();
    }
    return "accepted";
  };
  const auto rule_of = [](const auto& declaration) { return declaration.rule(); };
  const auto [albedo] = Lambertian::parameters();
  const auto [metal_albedo, fuzz] = Metal::parameters();
  const auto [ior, fresnel] = Dielectric::parameters();
  EXPECT_NE(refusal(R"({"type": "lambertian", "albedo": [0.5, -1, 0.5]})")
                .find("/materials/m/albedo/1: " + rule_of(albedo) + ", got -1"),
            std::string::npos);
  EXPECT_NE(refusal(R"({"type": "metal", "albedo": [0.5, 0.5, 2], "fuzz": 0})")
                .find("/materials/m/albedo/2: " + rule_of(metal_albedo) + ", got 2"),
            std::string::npos);
  EXPECT_NE(refusal(R"({"type": "metal", "albedo": [0.5, 0.5, 0.5], "fuzz": -1})")
                .find("/materials/m/fuzz: " + rule_of(fuzz) + ", got -1"),
            std::string::npos);
  EXPECT_NE(refusal(R"({"type": "dielectric", "ior": 2e6})")
                .find("/materials/m/ior: " + rule_of(ior) + ", got 2e+06"),
            std::string::npos);
  EXPECT_NE(refusal(R"({"type": "dielectric", "ior": 1.5, "fresnel": "fast"})")
                .find("/materials/m/fresnel: must be " + fresnel.choice_list()),
            std::string::npos);
  // Required parameters are required, optional ones take their default, unknown ones are named.
  EXPECT_NE(refusal(R"({"type": "dielectric"})").find("missing field \"ior\""), std::string::npos);
  EXPECT_EQ(std::get<Metal>(read_back(R"({"type": "metal", "albedo": [1, 1, 1]})")).fuzz,
            *fuzz.fallback);
  EXPECT_EQ(std::get<Dielectric>(read_back(R"({"type": "dielectric", "ior": 1.5})")).fresnel,
            fresnel.fallback);
  EXPECT_NE(refusal(R"({"type": "lambertian", "albedo": [1, 1, 1], "fuzz": 0})")
                .find("/materials/m/fuzz: unknown field (expected one of: type, albedo)"),
            std::string::npos);
  EXPECT_NE(refusal(R"({"type": "plastic"})")
                .find("unknown material type 'plastic' (expected lambertian, metal or dielectric)"),
            std::string::npos);
}

}  // namespace
}  // namespace rtiow
