// A big scene file parsed on every core (read_scene_in_runs, core/scene_file/json_split.h) gives
// the scene the one-piece parse gives, bit for bit, whatever the windows and runs it is cut
// into; and it gives nothing (so the caller parses in one piece, for the message) for every
// text the one-piece parse refuses, including thousands of random corruptions of a valid one.

#include <gtest/gtest.h>

#include <xmmintrin.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <oneapi/tbb/task_arena.h>
#include <nlohmann/json.hpp>

#include "core/limits/error.h"
#include "core/scene/builtin_scenes.h"
#include "core/scene_file/scene_file.h"

namespace rtiow {
namespace {

// `text` in reads of at most `chunk` bytes.
std::function<std::size_t(char*, std::size_t)> reader(const std::string& text, std::size_t chunk) {
  return [&text, chunk, offset = std::size_t(0)](char* buffer, std::size_t size) mutable {
    const std::size_t n = std::min({size, chunk, text.size() - offset});
    std::memcpy(buffer, text.data() + offset, n);
    offset += n;
    return n;
  };
}

// Whether two reads agree: both nothing, or scenes that are the same (expect_same, below).
bool same_scene(const std::optional<Scene>& a, const std::optional<Scene>& b) {
  if (a.has_value() != b.has_value()) return false;
  return !a || (scene_to_json(*a) == scene_to_json(*b) &&
                a->spheres.material == b->spheres.material && a->name == b->name);
}

// In runs on this machine's cores, and again on 8 threads, where each window's names are
// resolved shard by shard on several cores (sharded_names.h): both must give the same.
std::optional<Scene> in_runs(const std::string& text, std::size_t run, std::size_t window,
                             std::size_t chunk = 1 << 20) {
  std::optional<Scene> here = read_scene_in_runs(reader(text, chunk), "t.json", run, window);
  std::optional<Scene> on_eight;
  tbb::task_arena(8).execute(
      [&] { on_eight = read_scene_in_runs(reader(text, chunk), "t.json", run, window); });
  EXPECT_TRUE(same_scene(here, on_eight)) << "on 8 threads, window " << window << ", run " << run;
  return here;
}

std::optional<Scene> in_one_piece(const std::string& text) {
  try {
    return parse_scene(text, "t.json");
  } catch (const InvalidInput&) {
    return std::nullopt;
  }
}

// Two scenes are the same when they write the same text: every float is written in its
// shortest exact form, and materials by index, so the material order counts too.
void expect_same(const Scene& a, const Scene& b, const std::string& what) {
  EXPECT_EQ(scene_to_json(a), scene_to_json(b)) << what;
  EXPECT_EQ(a.spheres.material, b.spheres.material) << what;
  EXPECT_EQ(a.name, b.name) << what;
}

const std::vector<std::size_t> kSizes = {1, 2, 7, 64, 1000, std::size_t(1) << 20};

TEST(SceneInRuns, GivesTheOnePieceSceneForAnyWindowsAndRuns) {
  for (const char* name : {"cover", "materials", "spheres:600"}) {
    const std::string text = scene_to_json(make_builtin_scene(name, 1));
    const Scene whole = parse_scene(text, "t.json");
    for (const std::size_t window : kSizes) {
      for (const std::size_t run : {std::size_t(1), std::size_t(300), std::size_t(1) << 20}) {
        const std::optional<Scene> split = in_runs(text, run, window, 3);
        const std::string what = std::string(name) + ", window " + std::to_string(window) +
                                 ", run " + std::to_string(run);
        ASSERT_TRUE(split.has_value()) << what;
        expect_same(*split, whole, what);
      }
    }
  }
}

TEST(SceneInRuns, KeepsTheOrderInWhichNamesFirstAppear) {
  // Spheres before materials, a name used before it is defined, names with escapes and
  // nested values, laid out otherwise than rtiow writes them.
  const std::string text = R"({"spheres": [
      {"center": [0, -1000, 0], "radius": 1000, "material": "gro\"und"},
      {"material": "b", "radius": 0.5, "center": [1, 0.5, 0]} ,
      {"center": [2, 0.5, 0], "radius": -0.45, "material": "gro\"und"}],
    "version": 1,
    "materials": {"b": {"type": "metal", "albedo": [0.7, 0.6, 0.5], "fuzz": 0.1},
                  "unused": {"type": "dielectric", "ior": 1.5},
                  "gro\"und": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}},
    "camera": {"lookfrom": [13, 2, 3], "lookat": [0, 0, 0], "vfov": 20},
    "image": {"width": 40, "height": 20}})";
  const Scene whole = parse_scene(text, "t.json");
  for (const std::size_t window : kSizes) {
    for (const std::size_t run : {std::size_t(1), std::size_t(1) << 20}) {
      const std::optional<Scene> split = in_runs(text, run, window);
      ASSERT_TRUE(split.has_value()) << "window " << window << ", run " << run;
      expect_same(*split, whole, "window " + std::to_string(window));
    }
  }
  // Pretty-printed by another writer: the same scene again.
  const std::string pretty = nlohmann::ordered_json::parse(text).dump(4);
  const std::optional<Scene> split = in_runs(pretty, 50, 64);
  ASSERT_TRUE(split.has_value());
  expect_same(*split, whole, "pretty-printed");
}

TEST(SceneInRuns, ReadsEscapesAtEveryPlaceInABlockAndAWindow) {
  // The scan takes 64 bytes at a time where they hold no backslash: an escaped quote or
  // backslash at each offset of a block, and a window ending on one, still split right.
  const std::string head =
      R"({"materials": {"a\\\"b": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]},
      "c\"": {"type": "metal", "albedo": [0.7, 0.6, 0.5], "fuzz": 0}}, "spheres": [)";
  const std::string tail = R"({"center": [0, -1000, 0], "radius": 1000, "material": "a\\\"b"},
      {"center": [1, 0.5, 0], "radius": 0.5, "material": "c\""},
      {"center": [2, 0.5, 0], "radius": 0.5, "material": "a\\\"b"}],
    "camera": {"lookfrom": [13, 2, 3], "lookat": [0, 0, 0], "vfov": 20}, "version": 1,
    "image": {"width": 40, "height": 20}})";
  for (std::size_t pad = 0; pad < 140; ++pad) {
    const std::string text = head + std::string(pad, ' ') + tail;
    const Scene whole = parse_scene(text, "t.json");
    ASSERT_EQ(whole.materials.size(), 2u);
    for (const std::size_t window : {std::size_t(64), std::size_t(97), std::size_t(1) << 20}) {
      const std::optional<Scene> split = in_runs(text, 1, window);
      ASSERT_TRUE(split.has_value()) << "pad " << pad << ", window " << window;
      expect_same(*split, whole, "pad " + std::to_string(pad));
    }
  }
}

TEST(SceneInRuns, ReadsEveryShapeOfNumberAsTheOnePieceParseDoes) {
  // A run reads a number's text straight to a double; the one-piece parse reads a whole
  // number as an integer first ("-0" is then +0), an underflow through strtod, and a
  // whole number past 64 bits as a double.
  const std::vector<std::string> numbers = {"-0",
                                            "0",
                                            "-0.0",
                                            "0e0",
                                            "-0e-0",
                                            "1e-400",
                                            "-4.9e-324",
                                            "2.2250738585072011e-308",
                                            "18446744073709551616",
                                            "-9223372036854775809",
                                            "9007199254740993",
                                            "1E2",
                                            "0.1e1",
                                            "-12",
                                            "123456789012345678901234567890",
                                            "3.4028235677973366e38",
                                            "1e-45",
                                            "-1e-40"};
  for (const std::string& x : numbers) {
    const std::string fuzz = x.front() == '-' || x.size() > 6 ? "0" : x;
    const std::string text = R"({"version": 1, "name": "n",
      "camera": {"lookfrom": [13, 2, 3], "lookat": [0, 0, 0], "vfov": 20},
      "image": {"width": 40, "height": 20},
      "materials": {"g": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]},
                    "m": {"type": "metal", "albedo": [0.7, 0.6, 0.5], "fuzz": )" +
                             fuzz + R"(}},
      "spheres": [{"center": [)" +
                             x + ", " + x + ", " + x + R"(], "radius": 1000,
                   "material": "g"},
                  {"center": [1, )" +
                             x + R"(, 0], "radius": 0.5, "material": "m"}]})";
    const std::optional<Scene> whole = in_one_piece(text);
    const std::optional<Scene> split = in_runs(text, 1, 64);
    ASSERT_EQ(whole.has_value(), split.has_value()) << x;
    if (!whole) continue;
    expect_same(*split, *whole, x);
    for (std::size_t i = 0; i < whole->spheres.size(); ++i) {
      EXPECT_EQ(std::bit_cast<std::uint32_t>(split->spheres.center_x[i]),
                std::bit_cast<std::uint32_t>(whole->spheres.center_x[i]))
          << x;
      EXPECT_EQ(std::bit_cast<std::uint32_t>(split->spheres.center_y[i]),
                std::bit_cast<std::uint32_t>(whole->spheres.center_y[i]))
          << x;
    }
  }
}

TEST(SceneInRuns, ReadsDenormalsAsTheCallerDoesWhateverTheWorkersWereLeftWith) {
  // TBB's workers run an arena's tasks under the floating-point settings of the thread that
  // started it; an Embree build that starts TBB leaves them flushing denormals to zero. Here
  // an arena starts so on purpose, and the split read, most of it on those workers, must
  // still give each sphere the denormal the one-piece read gives.
  std::string text = R"({"version": 1,
    "camera": {"lookfrom": [13, 2, 3], "lookat": [0, 0, 0], "vfov": 20},
    "image": {"width": 40, "height": 20},
    "materials": {"g": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}}, "spheres": [)";
  for (int i = 0; i < 20000; ++i) {
    text.append(i ? ",\n" : "\n").append(R"({"center": [1e-45, -3e-42, )");
    text.append(std::to_string(i)).append(R"(], "radius": 0.5, "material": "g"})");
  }
  text.append("]}");
  const Scene whole = parse_scene(text, "t.json");
  ASSERT_EQ(std::bit_cast<std::uint32_t>(whole.spheres.center_x[0]), 1u);
  const unsigned settings = _mm_getcsr();
  _mm_setcsr(settings | 0x8040);  // flush to zero, denormals are zero
  tbb::task_arena arena(2);
  arena.initialize();
  _mm_setcsr(settings);
  std::optional<Scene> split;
  arena.execute([&] { split = read_scene_in_runs(reader(text, 1 << 20), "t.json", 4096, 4096); });
  ASSERT_TRUE(split.has_value());
  expect_same(*split, whole, "denormals");
  for (std::size_t i = 0; i < whole.spheres.size(); ++i) {
    ASSERT_EQ(std::bit_cast<std::uint32_t>(split->spheres.center_x[i]), 1u) << i;
    ASSERT_EQ(std::bit_cast<std::uint32_t>(split->spheres.center_y[i]),
              std::bit_cast<std::uint32_t>(whole.spheres.center_y[i]))
        << i;
  }
}

TEST(SceneInRuns, RefusesWhatTheOnePieceParseRefuses) {
  const std::string base = R"({"version": 1, "name": "s",
    "camera": {"lookfrom": [13, 2, 3], "lookat": [0, 0, 0], "vfov": 20},
    "image": {"width": 40, "height": 20},
    "materials": {"g": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]},
                  "m": {"type": "metal", "albedo": [0.7, 0.6, 0.5], "fuzz": 0}},
    "spheres": [{"center": [0, -1000, 0], "radius": 1000, "material": "g"},
                {"center": [1, 0.5, 0], "radius": 0.5, "material": "m"},
                {"center": [2, 0.5, 0], "radius": 0.5, "material": "g"}]})";
  const std::vector<std::string> refused = {
      R"({"version": 1, "materials": {}, "spheres": []})",
      R"({"version": 1, "materials": {"a": 1, "a": 1}, "spheres": [1]})",
      "[1, 2]",
      "",
      R"({"materials": {"a": {}}, "spheres": [1, ]})",
      R"({"materials": {"a": {}}, "spheres": [ , 1]})",
      R"({"materials": {"a": {}}, "spheres": [1 2]})",
      R"({"materials": {"a": {}}, "spheres": [1,,2]})",
      R"({"materials": {"a": {}, , "b": {}}, "spheres": [1]})",
      R"({"materials": {"a": {}}, "spheres": [1]]})",
      R"({"materials": {"a": {}}, "spheres": [[1]})",
      R"({"materi\u0061ls": {}, "spheres": [1]})",
  };
  for (const std::string& text : refused) {
    ASSERT_FALSE(in_one_piece(text).has_value()) << text;
    for (const std::size_t window : kSizes) {
      EXPECT_FALSE(in_runs(text, 1, window).has_value()) << "window " << window << ": " << text;
    }
  }

  // Random corruptions: a byte deleted, replaced by a structural one or duplicated, a span
  // cut out or repeated. Whatever the parse in runs accepts, the one-piece parse accepts as
  // the same scene; whatever that accepts, so does the parse in runs.
  std::mt19937 rng(2026);
  const std::string structural = "{}[],:\"\\ 0e-.";
  int accepted = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    std::string text = base;
    const int edits = 1 + int(rng() % 3);
    for (int e = 0; e < edits && !text.empty(); ++e) {
      const std::size_t at = rng() % text.size();
      switch (rng() % 5) {
        case 0:
          text.erase(at, 1);
          break;
        case 1:
          text[at] = structural[rng() % structural.size()];
          break;
        case 2:
          text.insert(at, 1, text[at]);
          break;
        case 3:
          text.erase(at, std::min<std::size_t>(rng() % 12, text.size() - at));
          break;
        default: {
          const std::size_t length = std::min<std::size_t>(rng() % 40, text.size() - at);
          text.insert(at, text.substr(at, length));
        }
      }
    }
    const std::optional<Scene> whole = in_one_piece(text);
    const std::size_t window = kSizes[rng() % kSizes.size()];
    const std::optional<Scene> split = in_runs(text, 1 + rng() % 200, window, 1 + rng() % 64);
    ASSERT_EQ(split.has_value(), whole.has_value()) << "window " << window << ": " << text;
    if (whole) {
      ++accepted;
      expect_same(*split, *whole, text);
    }
  }
  EXPECT_GT(accepted, 20);  // some corruptions keep a valid scene (spaces, digits)
}

TEST(SceneInRuns, LeavesAHugeMemberToTheOnePieceParse) {
  // 2 MiB of spaces inside one sphere: valid, but carried from window to window it would be
  // copied again each time (a hostile file's quadratic cost), so the scan gives up on it.
  std::string text = scene_to_json(make_builtin_scene("materials", 1));
  text.insert(text.find("\"radius\""), std::string(std::size_t(2) << 20, ' '));
  ASSERT_TRUE(in_one_piece(text).has_value());
  EXPECT_FALSE(in_runs(text, 1 << 20, 64 << 10).has_value());
  // And a root value as big: the skeleton too.
  std::string name_text = scene_to_json(make_builtin_scene("materials", 1));
  name_text.insert(name_text.find("\"camera\""), std::string(std::size_t(2) << 20, '\n'));
  ASSERT_TRUE(in_one_piece(name_text).has_value());
  EXPECT_FALSE(in_runs(name_text, 1 << 20, 64 << 10).has_value());
}

TEST(SceneInRuns, ABigSceneFileLoadsAsTheOnePieceParseReadsIt) {
  const std::string text = scene_to_json(make_builtin_scene("spheres:40000", 3));
  ASSERT_GE(text.size(), kSplitFileBytes);  // so load_scene_file cuts it
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "rtiow_scene_in_runs_test.json";
  std::ofstream(path, std::ios::binary) << text;
  const Scene loaded = load_scene_file(path.string());
  expect_same(loaded, parse_scene(text, path.string()), "spheres:40000");

  // A file refused deep inside: the one-piece parse's message, line and column.
  std::string broken = text;
  const std::size_t at = broken.rfind("\"radius\":");
  broken.replace(at, 9, "\"radius\" ");
  std::ofstream(path, std::ios::binary) << broken;
  std::string message;
  try {
    load_scene_file(path.string());
  } catch (const InvalidInput& e) {
    message = e.what();
  }
  std::string expected;
  try {
    parse_scene(broken, path.string());
  } catch (const InvalidInput& e) {
    expected = e.what();
  }
  EXPECT_FALSE(expected.empty());
  EXPECT_EQ(message, expected);
  EXPECT_NE(message.find("expected ':' after a key"), std::string::npos) << message;
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace rtiow
