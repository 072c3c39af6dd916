// The core's folders form layers, with the command line (app/) on top: a file includes only its
// own folder and the folders below it, so a concept can be read (and reused) without what is
// built on it, and the core never reaches into the CLI. The order is docs/design.md's; a new
// folder must be placed in it before it can be included.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

// Lower numbers are lower layers; a file may include its own layer and any lower one.
const std::map<std::string, int>& layers() {
  static const std::map<std::string, int> order = {
      {"core/limits", 0},   {"core/parallel", 0}, {"core/version.h", 0},  {"core/version.cpp", 0},
      {"core/geometry", 1}, {"core/sampling", 2}, {"materials", 3},       {"core/film", 4}, {"core/denoise", 4},
      {"core/io", 5},       {"core/scene", 6},    {"core/scene_file", 7}, {"core/accel", 8},
      {"core/render", 9},   {"core/compare", 10}, {"core/session", 11},   {"core/measure", 12},
      {"core/rtiow.h", 13}, {"app", 14},
  };
  return order;
}

// The layer of a path relative to the source root ("core/io/error.h"), or -1 if unplaced.
int layer_of(const std::string& path) {
  for (const auto& [prefix, layer] : layers()) {
    if (path == prefix || path.rfind(prefix + "/", 0) == 0) return layer;
  }
  return -1;
}

struct Include {
  std::string from, to;
};

std::vector<Include> project_includes() {
  const fs::path root = RTIOW_SOURCE_DIR;
  const std::regex include(R"(^\s*#\s*include\s+"((core|materials|app)/[^"]+)\")");
  std::vector<Include> found;
  for (const char* top : {"core", "materials", "app"}) {
    for (const auto& entry : fs::recursive_directory_iterator(root / top)) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".h" && ext != ".cpp") continue;
      const std::string from = fs::relative(entry.path(), root).generic_string();
      std::ifstream in(entry.path());
      std::string line;
      std::smatch m;
      while (std::getline(in, line)) {
        if (std::regex_search(line, m, include)) found.push_back({from, m[1]});
      }
    }
  }
  return found;
}

TEST(Layering, EveryFolderIsPlaced) {
  for (const Include& i : project_includes()) {
    EXPECT_GE(layer_of(i.from), 0) << i.from << " is in no layer";
    EXPECT_GE(layer_of(i.to), 0) << i.to << " (included by " << i.from << ") is in no layer";
  }
}

TEST(Layering, NoIncludeRunsBackUp) {
  const std::vector<Include> includes = project_includes();
  ASSERT_GT(includes.size(), 100u) << "found too few includes to check";
  for (const Include& i : includes) {
    EXPECT_LE(layer_of(i.to), layer_of(i.from)) << i.from << " includes " << i.to << ", above it";
  }
}

}  // namespace
