// The hostile-input battery: the real executable, run as a hostile user would, one case per
// member of each class of bad input (structure, untraceable numbers, sizes and counts,
// output paths, part files, files that are not regular or are huge, and machine failures).
// Every case runs in a directory of its own holding a user's files (a scene, parts, an
// image of their own, a FIFO, links), under a memory cap (prlimit --as) and a time limit,
// and must end with
//   - the exit code of its class: 2 for wrong input, 1 for a failing machine;
//   - exactly one line on stderr, "rtiow: error: ...", printable, of sensible length,
//     naming the problem (each case names a piece of text the line must hold);
//   - every file in the directory byte-for-byte as it was, and no file added.

#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tests/test_files.h"

namespace {

namespace fs = std::filesystem;

using rtiow::test::slurp;

using rtiow::test::write_file;

// Runs rtiow with `args` in `dir` under the caps; stdout to `stdout_path`, stderr to
// `stderr_path`. Returns the exit code, or 128 + signal.
int run_capped(const fs::path& dir, const std::vector<std::string>& args,
               const std::string& stdout_path, const std::string& stderr_path,
               const std::vector<std::string>& extra_limits) {
  std::vector<std::string> command = {"prlimit", "--as=4294967296"};
  command.insert(command.end(), extra_limits.begin(), extra_limits.end());
  command.insert(command.end(), {"--", "timeout", "-s", "KILL", "120", RTIOW_BINARY});
  command.insert(command.end(), args.begin(), args.end());
  const pid_t pid = fork();
  if (pid == 0) {
    if (chdir(dir.c_str()) != 0) _exit(126);
    const int in = open("/dev/null", O_RDONLY);
    const int out = open(stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in < 0 || out < 0 || err < 0) _exit(126);
    dup2(in, 0), dup2(out, 1), dup2(err, 2);
    std::vector<char*> argv;
    for (std::string& a : command) argv.push_back(a.data());
    argv.push_back(nullptr);
    execvp(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  const int code = WEXITSTATUS(status);
  return code == 128 + SIGKILL ? 128 + SIGKILL : code;  // timeout -s KILL reports 137
}

// What a directory holds: name -> kind and bytes (links by their target, not followed).
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const std::string name = fs::relative(entry.path(), dir).string();
    const auto status = entry.symlink_status();
    if (fs::is_symlink(status)) {
      files[name] = "link:" + fs::read_symlink(entry.path()).string();
    } else if (fs::is_regular_file(status)) {
      // Bytes for every file but the sparse 3 GiB one, which is compared by size and time.
      const bool huge = entry.file_size() > (std::uintmax_t(256) << 20);
      files[name] =
          "file:" + std::to_string(entry.file_size()) + ":" +
          (huge ? std::to_string(fs::last_write_time(entry.path()).time_since_epoch().count())
                : std::to_string(std::hash<std::string>{}(slurp(entry.path()))));
    } else {
      files[name] = fs::is_directory(status) ? "dir" : "other";
    }
  }
  return files;
}

constexpr const char* kScene = R"({
  "version": 1,
  "name": "user scene",
  "camera": {"lookfrom": [0, 0, 0], "lookat": [0, 0, -1], "vfov": 90},
  "image": {"width": 8, "height": 4, "spp": 4, "depth": 4},
  "materials": {"red": {"type": "lambertian", "albedo": [0.8, 0.1, 0.1]},
                "glass": {"type": "dielectric", "ior": 1.5}},
  "spheres": [{"center": [0, 0, -1], "radius": 0.5, "material": "red"},
              {"center": [0, -100.5, -1], "radius": 100, "material": "glass"}]
})";

// kScene with `from` replaced by `to` (the test fails if `from` is not in it).
std::string scene_with(const std::string& from, const std::string& to) {
  std::string text = kScene;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: " << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// Part files of kScene (and of another render) made once and shared by the cases; made in a
// private directory and renamed into place, as CTest runs cases in parallel processes.
// `exr` with its box2i attribute `name` made 0..8191 on both axes.
std::string with_box(std::string exr, const std::string& name) {
  const std::string key = name + std::string("\0box2i\0", 7);
  const std::size_t at = exr.find(key);
  EXPECT_NE(at, std::string::npos) << name;
  if (at == std::string::npos) return exr;
  const std::int32_t box[4] = {0, 0, 8191, 8191};
  exr.replace(at + key.size() + 4, sizeof box, reinterpret_cast<const char*>(box), sizeof box);
  return exr;
}

std::uint32_t crc32(const std::string& bytes) {
  std::uint32_t crc = 0xffffffffu;
  for (const unsigned char byte : bytes) {
    crc ^= byte;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

std::string big_endian(std::uint32_t v) {
  return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

std::string png_chunk(const std::string& type, const std::string& data) {
  return big_endian(std::uint32_t(data.size())) + type + data + big_endian(crc32(type + data));
}

// A valid PNG header (8-bit RGB, checksums right) that says width x height, with one tiny
// stored deflate block of pixel data.
std::string png_claiming(std::uint32_t width, std::uint32_t height) {
  const std::string header =
      big_endian(width) + big_endian(height) + std::string("\x08\x02\0\0\0", 5);
  const std::string deflate("\x78\x01\x01\x01\x00\xfe\xff\x00\x00\x01\x00\x01", 12);
  return std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", header) +
         png_chunk("IDAT", deflate) + png_chunk("IEND", "");
}

fs::path fixtures() {
  // Named by version: a build tree keeps the fixtures of an older suite under another name.
  const fs::path dir = fs::path(RTIOW_TEST_OUTPUT_DIR) / "hostile-fixtures-4";
  if (fs::exists(dir / "complete")) return dir;
  const fs::path work =
      fs::path(RTIOW_TEST_OUTPUT_DIR) / ("hostile-fixtures." + std::to_string(getpid()));
  fs::remove_all(work);
  fs::create_directories(work);
  write_file(work / "scene.json", kScene);
  const auto render = [&](const std::string& args) {
    const std::string command = std::string("cd ") + work.string() + " && " + RTIOW_BINARY +
                                " render -q scene.json " + args;
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
  };
  render("--part 0/2 -o part0.exr");
  render("--part 1/2 -o part1.exr");
  render("--seed 7 --part 1/2 -o other-render.exr");
  render("-o plain.exr");
  render("--part 0/2 --passes albedo,normal,depth -o passes0.exr");
  // Part files whose header or sums lie, written field by field and word by word: `edit`
  // changes the header, `words` pixel 0's words (by channel name) of the part `from`.
  using Words = std::function<void(std::function<std::uint32_t&(const std::string&)>)>;
  const auto crafted = [&](const std::string& name,
                           const std::function<void(OIIO::ImageSpec&)>& edit,
                           const std::string& from = "part0.exr", const Words& words = {}) {
    auto in = OIIO::ImageInput::open((work / from).string());
    ASSERT_TRUE(in);
    OIIO::ImageSpec spec = in->spec();
    std::vector<std::uint32_t> data(std::size_t(spec.image_pixels()) * std::size_t(spec.nchannels));
    ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT, data.data()));
    edit(spec);
    if (words) {
      words([&](const std::string& channel) -> std::uint32_t& {
        const int at = spec.channelindex(channel);
        EXPECT_GE(at, 0) << "test bug: no channel " << channel;
        return data[std::size_t(std::max(at, 0))];
      });
    }
    spec.channelformats.assign(std::size_t(spec.nchannels), OIIO::TypeDesc::UINT);
    auto out = OIIO::ImageOutput::create((work / name).string());
    ASSERT_TRUE(out && out->open((work / name).string(), spec) &&
                out->write_image(OIIO::TypeDesc::UINT, data.data()) && out->close());
  };
  crafted("samples-not-a-number.exr", [](auto& s) { s.attribute("rtiow:part_samples", "12x"); });
  crafted("zero-samples.exr", [](auto& s) { s.attribute("rtiow:part_samples", "0"); });
  crafted("overflowing-range.exr",
          [](auto& s) { s.attribute("rtiow:part_first_sample", "18446744073709551615"); });
  crafted("huge-job.exr", [](auto& s) { s.attribute("rtiow:part_job_samples", "1099511627776"); });
  crafted("no-job.exr", [](auto& s) { s.erase_attribute("rtiow:part_job_samples"); });
  crafted("negative-samples.exr", [](auto& s) { s.attribute("rtiow:part_samples", "-2"); });
  crafted("older-version.exr", [](auto& s) { s.attribute("rtiow:version", "0.0.1"); });
  crafted("passes-garbage.exr", [](auto& s) { s.attribute("rtiow:passes", "albedo,sparkle"); });
  crafted("passes-without-sums.exr", [](auto& s) { s.attribute("rtiow:passes", "depth"); });
  // Sums no samples can add up to, one word each (a checkpoint refuses the same).
  const auto same = [](OIIO::ImageSpec&) {};
  crafted("sum-word.exr", same, "part0.exr", [](auto word) { word("sum.R.1") = 0x7fffffffu; });
  crafted("square-words.exr", same, "part0.exr", [](auto word) {
    for (const char* w : {"squares.G.0", "squares.G.1", "squares.G.2", "squares.G.3"}) {
      word(w) = 0x7fffffffu;
    }
  });
  crafted("odd-word.exr", same, "part0.exr", [](auto word) { word("odd.B.2") = 1; });
  crafted("odd-above-sum.exr", same, "part0.exr", [](auto word) {
    for (const char* w : {".0", ".1", ".2", ".3"})
      word(std::string("odd.G") + w) = word(std::string("sum.G") + w);
    word("odd.G.0") += 1;  // the sum's low word is far from 2^32 - 1 for a pixel of about 1
  });
  crafted("count-word.exr", [](auto& s) { s.attribute("rtiow:part_samples", "1"); });
  crafted("first-hit-word.exr", same, "passes0.exr",
          [](auto word) { word("first_hit.albedo.R.1") = 5; });
  crafted("normal-words.exr", same, "passes0.exr", [](auto word) {
    for (const char* axis : {"X", "Y", "Z"}) {  // each axis within its bound, together too long
      const std::string c = std::string("first_hit.N.") + axis;
      word(c + ".0") = 0, word(c + ".1") = 2, word(c + ".2") = 0, word(c + ".3") = 0;
    }
  });
  const std::string part = slurp(work / "part0.exr");
  write_file(work / "truncated.exr", part.substr(0, part.size() / 2));
  // Headers that claim far more pixels than their files hold: a part of 8192x8192 (10 GB of
  // sums) and a 30000x30000 PNG, each a few KB.
  write_file(work / "huge-header.exr", with_box(with_box(part, "dataWindow"), "displayWindow"));
  write_file(work / "huge-header.png", png_claiming(30000, 30000));
  write_file(work / "complete", "");
  std::error_code ignored;
  fs::rename(work, dir, ignored);  // another process may have won: its files are the same
  if (ignored) fs::remove_all(work);
  return dir;
}

struct Case {
  std::string name;
  int exit_code;                               // 2: wrong input; 1: the machine failed
  std::string needle;                          // the error line must hold this
  std::vector<std::string> args;               // to rtiow, in the case's directory
  std::map<std::string, std::string> files{};  // more files of the user's
  std::vector<std::string> limits{};           // more prlimit options
  std::string stdout_path{};                   // default: a file outside the directory
};

// A render of the user's scene with these options added, to an output of the user's.
std::vector<std::string> render(std::vector<std::string> args) {
  args.insert(args.begin(), {"render", "-q"});
  return args;
}

std::vector<Case> structure_cases() {
  return {
      {"EmptyFile", 2, "line 1, column 1", render({"s.json"}), {{"s.json", ""}}},
      {"OnlySpaces", 2, "unexpected end of input", render({"s.json"}), {{"s.json", "   \n\n "}}},
      {"Garbage",
       2,
       "is not a scene file: a scene file is a JSON object",
       render({"s.json"}),
       {{"s.json", "\x01\x02\x7f\xff{"}}},
      {"NulByte", 2, "syntax error", render({"s.json"}), {{"s.json", std::string("{\0}", 3)}}},
      {"Truncated",
       2,
       "missing closing quote",
       render({"s.json"}),
       {{"s.json", std::string(kScene).substr(0, 200)}}},
      {"TrailingGarbage",
       2,
       "expected end of input",
       render({"s.json"}),
       {{"s.json", std::string(kScene) + " {}"}}},
      {"DeepArrays",
       2,
       "nested deeper than the limit of 32",
       render({"s.json"}),
       {{"s.json",
         scene_with("\"version\": 1,", "\"version\": 1, \"x\": " + std::string(200000, '[') +
                                           std::string(200000, ']') + ",")}}},
      {"DeepObjects",
       2,
       "nested deeper than the limit",
       render({"s.json"}),
       {{"s.json",
         [] {
           std::string t;
           for (int i = 0; i < 100000; ++i) t += "{\"a\":";
           return t + "1" + std::string(100000, '}');
         }()}}},
      {"DeepUnclosed",
       2,
       "nested deeper",
       render({"s.json"}),
       {{"s.json", "{\"a\": " + std::string(5000000, '[')}}},
      {"DeepInsideCamera",
       2,
       "nested deeper",
       render({"s.json"}),
       {{"s.json",
         scene_with("\"vfov\": 90", "\"vfov\": " + std::string(40, '[') + std::string(40, ']'))}}},
      {"DuplicateRootKey",
       2,
       "the key 'camera' appears twice",
       render({"s.json"}),
       {{"s.json", scene_with("\"version\": 1,", "\"version\": 1, \"camera\": {},")}}},
      {"DuplicateVersion",
       2,
       "the key 'version' appears twice",
       render({"s.json"}),
       {{"s.json", scene_with("\"version\": 1,", "\"version\": 1, \"version\": 1,")}}},
      {"DuplicateCameraKey",
       2,
       "the key 'vfov' appears twice",
       render({"s.json"}),
       {{"s.json", scene_with("\"vfov\": 90", "\"vfov\": 90, \"vfov\": 30")}}},
      {"DuplicateImageKey",
       2,
       "the key 'spp' appears twice",
       render({"s.json"}),
       {{"s.json", scene_with("\"spp\": 4", "\"spp\": 4, \"spp\": 400")}}},
      {"DuplicateMaterialName",
       2,
       "/materials/red: a second material of this name",
       render({"s.json"}),
       {{"s.json", scene_with("\"glass\":", "\"red\":")}}},
      {"DuplicateMaterialField",
       2,
       "the key 'albedo' appears twice",
       render({"s.json"}),
       {{"s.json", scene_with("[0.8, 0.1, 0.1]", "[0.8, 0.1, 0.1], \"albedo\": [1, 1, 1]")}}},
      {"DuplicateSphereField",
       2,
       "the key 'radius' appears twice",
       render({"s.json"}),
       {{"s.json", scene_with("\"radius\": 0.5", "\"radius\": 0.5, \"radius\": 5")}}},
      {"DuplicateMaterialsObject",
       2,
       "the key 'materials' appears twice",
       render({"s.json"}),
       {{"s.json", scene_with("\"version\": 1,", "\"version\": 1, \"materials\": {},")}}},
      {"HugeKey",
       2,
       "a key of 20000000 bytes is longer than the limit of 4096",
       render({"s.json"}),
       {{"s.json", scene_with("\"version\": 1,",
                              "\"version\": 1, \"" + std::string(20000000, 'k') + "\": 1,")}}},
      {"HugeString",
       2,
       "a string of 5000000 bytes",
       render({"s.json"}),
       {{"s.json", scene_with("\"user scene\"", "\"" + std::string(5000000, 'n') + "\"")}}},
      {"ControlCharactersInKey",
       2,
       "unknown field",
       render({"s.json"}),
       {{"s.json",
         scene_with("\"version\": 1,", "\"version\": 1, \"a\\nb\\u0007\\u001b[2J\": 1,")}}},
      {"LongUnknownKey",
       2,
       "unknown field",
       render({"s.json"}),
       {{"s.json",
         scene_with("\"version\": 1,", "\"version\": 1, \"" + std::string(4000, 'x') + "\": 1,")}}},
      {"WholeValueNotDumped",
       2,
       "got an array of 100001 values",
       render({"s.json"}),
       {{"s.json", scene_with(
                       "\"vfov\": 90", "\"vfov\": [" +
                                           [] {
                                             std::string a = "0";
                                             for (int i = 0; i < 100000; ++i) a += ",0";
                                             return a;
                                           }() +
                                           "]")}}},
      {"NotAnObject",
       2,
       "a scene file is a JSON object, beginning with '{', and this one begins "
       "with '['",
       render({"s.json"}),
       {{"s.json", "[1, 2, 3]"}}},
      {"NumberOverflow",
       2,
       "number overflow",
       render({"s.json"}),
       {{"s.json", scene_with("\"radius\": 0.5", "\"radius\": 1e999")}}},
      {"NegativeOverflow",
       2,
       "number overflow",
       render({"s.json"}),
       {{"s.json", scene_with("\"radius\": 0.5", "\"radius\": -1e999")}}},
      {"NanLiteral",
       2,
       "syntax error",
       render({"s.json"}),
       {{"s.json", scene_with("\"radius\": 0.5", "\"radius\": NaN")}}},
      {"InvalidUtf8",
       2,
       "syntax error",
       render({"s.json"}),
       {{"s.json", scene_with("\"user scene\"", "\"\xc3\x28\"")}}},
      {"UnknownMaterialName",
       2,
       "no material named 'blue'",
       render({"s.json"}),
       {{"s.json", scene_with("\"material\": \"red\"", "\"material\": \"blue\"")}}},
      {"NameWithNul",
       2,
       "unknown field",
       render({"s.json"}),
       {{"s.json", scene_with("\"version\": 1,", "\"version\": 1, \"nul\\u0000key\": 1,")}}},
  };
}

std::vector<Case> number_cases() {
  return {
      {"CameraFarAway",
       2,
       "/camera/lookfrom/0: is beyond the limit of +-1e+15",
       render({"s.json"}),
       {{"s.json", scene_with("\"lookfrom\": [0, 0, 0]", "\"lookfrom\": [1e19, 0, 0]")}}},
      {"CameraAtFloatInfinity",
       2,
       "/camera/lookfrom/2: is beyond the limit",
       render({"s.json"}),
       {{"s.json", scene_with("\"lookfrom\": [0, 0, 0]", "\"lookfrom\": [0, 0, 1e39]")}}},
      {"LookatFar",
       2,
       "/camera/lookat/1: is beyond",
       render({"s.json"}),
       {{"s.json", scene_with("\"lookat\": [0, 0, -1]", "\"lookat\": [0, 1e16, -1]")}}},
      {"VupHuge",
       2,
       "/camera/vup/0: is beyond",
       render({"s.json"}),
       {{"s.json", scene_with("\"vfov\": 90", "\"vfov\": 90, \"vup\": [1e300, 1, 0]")}}},
      {"FocusFar",
       2,
       "/camera/focus_distance: is beyond",
       render({"s.json"}),
       {{"s.json", scene_with("\"vfov\": 90", "\"vfov\": 90, \"focus_distance\": 1e20")}}},
      {"FocusTiny",
       2,
       "focus distance must be from 1e-12",
       render({"s.json"}),
       {{"s.json", scene_with("\"vfov\": 90", "\"vfov\": 90, \"focus_distance\": 1e-300")}}},
      {"ApertureHuge",
       2,
       "/camera/aperture: is beyond",
       render({"s.json"}),
       {{"s.json", scene_with("\"vfov\": 90", "\"vfov\": 90, \"aperture\": 1e30")}}},
      {"SphereFar",
       2,
       "/spheres/0/center/0: is beyond",
       render({"s.json"}),
       {{"s.json", scene_with("[0, 0, -1], \"radius\"", "[1e16, 0, -1], \"radius\"")}}},
      {"RadiusHuge",
       2,
       "/spheres/0/radius: is beyond",
       render({"s.json"}),
       {{"s.json", scene_with("\"radius\": 0.5", "\"radius\": 1e39")}}},
      {"RadiusRoundsToZero",
       2,
       "/spheres/0/radius: must not be 0",
       render({"s.json"}),
       {{"s.json", scene_with("\"radius\": 0.5", "\"radius\": 1e-60")}}},
      {"RadiusDenormal",  // Embree's build would flush its box to nothing
       2,
       "/spheres/0/radius: must be at least 1.2e-38 in size",
       render({"s.json"}),
       {{"s.json", scene_with("\"radius\": 0.5", "\"radius\": 1e-39")}}},
      {"IorZero",
       2,
       "/materials/glass/ior: must be from 0.001 to 1e+06",
       render({"s.json"}),
       {{"s.json", scene_with("\"ior\": 1.5", "\"ior\": 0")}}},
      {"IorHuge",
       2,
       "/materials/glass/ior: must be from",
       render({"s.json"}),
       {{"s.json", scene_with("\"ior\": 1.5", "\"ior\": 1e30")}}},
      {"AlbedoAboveOne",
       2,
       "/materials/red/albedo/0: must be in [0, 1]",
       render({"s.json"}),
       {{"s.json", scene_with("[0.8, 0.1, 0.1]", "[8, 0.1, 0.1]")}}},
      {"AspectTiny",
       2,
       "/image/aspect_ratio: gives a height of",
       render({"s.json"}),
       {{"s.json", scene_with("\"height\": 4", "\"aspect_ratio\": 1e-300")}}},
      {"AspectHuge",
       2,
       "/image/aspect_ratio: gives a height of 0 pixels",
       render({"s.json"}),
       {{"s.json", scene_with("\"height\": 4", "\"aspect_ratio\": 1e300")}}},
      {"WidthBeyondInt64",
       2,
       "/image/width: must be from 1 to",
       render({"s.json"}),
       {{"s.json", scene_with("\"width\": 8", "\"width\": 18446744073709551615")}}},
      {"WidthAsFloat",
       2,
       "/image/width: must be from 1 to",
       render({"s.json"}),
       {{"s.json", scene_with("\"width\": 8", "\"width\": 1e30")}}},
      {"SppHuge",
       2,
       "/image/spp: must be from 1",
       render({"s.json"}),
       {{"s.json", scene_with("\"spp\": 4", "\"spp\": 99999999999")}}},
      {"DepthHuge",
       2,
       "/image/depth: must be from 0 to 65536",
       render({"s.json"}),
       {{"s.json", scene_with("\"depth\": 4", "\"depth\": 70000")}}},
      {"CliLookfromFar", 2, "lookfrom[0] must be finite and within +-1e+15",
       render({"--lookfrom", "1e19,0,0"})},
      {"CliLookfromInfinite", 2, "lookfrom[1] must be finite", render({"--lookfrom", "0,1e39,0"})},
      {"CliLookfromNan", 2, "lookfrom[2] must be finite", render({"--lookfrom", "0,0,nan"})},
      {"CliLookatFar", 2, "lookat[2] must be finite", render({"--lookat", "0,0,-1e300"})},
      {"CliVupZero", 2, "vup is the zero vector", render({"--vup", "0,0,0"})},
      {"CliVupHuge", 2, "vup[0] must be finite", render({"--vup", "1e300,1,0"})},
      {"CliVfovZero", 2, "vfov must lie strictly between", render({"--vfov", "0"})},
      {"CliVfovStraight", 2, "vfov must lie strictly between", render({"--vfov", "180"})},
      {"CliVfovNan", 2, "vfov must lie strictly between", render({"--vfov", "nan"})},
      {"CliApertureNegative", 2, "aperture must be from 0", render({"--aperture", "-1"})},
      {"CliApertureHuge", 2, "aperture must be from 0", render({"--aperture", "1e300"})},
      {"CliApertureInf", 2, "aperture must be from 0", render({"--aperture", "inf"})},
      {"CliFocusZero", 2, "focus distance must be from", render({"--focus-dist", "0"})},
      {"CliFocusHuge", 2, "focus distance must be from", render({"--focus-dist", "1e300"})},
      {"CliRaysTooWide", 2, "its rays reach",
       render({"--width", "1048576", "--height", "1", "--vfov", "179.99999", "--focus-dist", "1e14",
               "--spp", "1"})},
      {"NaiveAcceleratorToo", 2, "lookfrom[0] must be finite",
       render({"--accel", "naive", "--lookfrom", "1e19,0,0"})},
  };
}

std::vector<Case> size_cases() {
  return {
      {"WidthZero", 2, "width must be > 0", render({"--width", "0"})},
      {"WidthNegative", 2, "width must be > 0", render({"--width", "-5"})},
      {"WidthTooLarge", 2, "each side must be at most 1048576",
       render({"--width", "1048577", "--height", "1"})},
      {"WidthBeyondInt", 2, "--width", render({"--width", "99999999999"})},
      {"WidthNotANumber", 2, "--width", render({"--width", "ten"})},
      {"WidthWithNewline", 2, "--width = 1\\n0", render({"--width", "1\n0"})},
      {"HeightZero", 2, "height must be > 0", render({"--width", "8", "--height", "0"})},
      {"HeightZeroAlone", 2, "height must be > 0, got 0", render({"--height", "0"})},
      {"TooManyPixels", 2, "more than 2^31 pixels",
       render({"--width", "1048576", "--height", "1048576"})},
      {"DerivedHeightZero",
       2,
       "aspect ratio gives a height of 0 pixels",
       render({"wide.json", "--width", "1"}),
       {{"wide.json", scene_with("\"height\": 4", "\"aspect_ratio\": 16")}}},
      {"DerivedWidthTooLarge",
       2,
       "aspect ratio gives a width of",
       render({"wide.json", "--height", "1048576"}),
       {{"wide.json", scene_with("\"height\": 4", "\"aspect_ratio\": 16")}}},
      {"SppZero", 2, "spp must be > 0", render({"--spp", "0"})},
      {"SppNegative", 2, "spp must be > 0", render({"--spp", "-4"})},
      {"SppBeyondInt", 2, "--spp", render({"--spp", "4294967296"})},
      {"DepthNegative", 2, "depth must be from 0 to 65536", render({"--depth", "-1"})},
      {"CliDepthHuge", 2, "depth must be from 0 to 65536", render({"--depth", "2000000000"})},
      {"SeedNegative", 2, "--seed: must not be negative", render({"--seed", "-1"})},
      {"SeedBeyond64Bits", 2, "--seed", render({"--seed", "18446744073709551616"})},
      {"SeedText", 2, "--seed", render({"--seed", "abc"})},
      {"SceneSeedNegative", 2, "--scene-seed: must not be negative",
       render({"--scene-seed", "-3"})},
      {"ThreadsNegative", 2, "threads must be from 0", render({"--threads", "-1"})},
      {"ThreadsBeyondPool", 2, "threads must be from 0 (all cores) to 1024",
       render({"--threads", "100000"})},
      {"ThreadsBeyondInt", 2, "--threads", render({"--threads", "99999999999"})},
      {"PartZeroShares", 2, "need 0 <= i < n", render({"--part", "0/0", "-o", "p.exr"})},
      {"PartIndexTooLarge", 2, "need 0 <= i < n", render({"--part", "2/2", "-o", "p.exr"})},
      {"PartNegative", 2, "expected i/n", render({"--part", "-1/2", "-o", "p.exr"})},
      {"PartOverflow", 2, "expected i/n",
       render({"--part", "18446744073709551616/2", "-o", "p.exr"})},
      {"PartHugeCount", 2, "do not make 18446744073709551615 shares",
       render({"--part", "1/18446744073709551615", "-o", "p.exr"})},
      {"PartTooManyShares", 2, "do not make 5 shares",
       render({"--spp", "4", "--part", "0/5", "-o", "p.exr"})},
      {"PartGarbage", 2, "expected i/n", render({"--part", "1/2/3", "-o", "p.exr"})},
      {"PartSpaces", 2, "expected i/n", render({"--part", " 1/2", "-o", "p.exr"})},
      {"PartToPng", 2, "must be .exr", render({"--part", "0/2", "-o", "p.png"})},
      {"RangeEmpty", 2, "need A < B", render({"--sample-range", "5:5", "-o", "p.exr"})},
      {"RangeBackwards", 2, "need A < B", render({"--sample-range", "6:5", "-o", "p.exr"})},
      {"RangeBeyondJob", 2, "need A < B <= the job's 500",
       render({"--sample-range", "0:18446744073709551615", "-o", "p.exr"})},
      {"RangeOverflow", 2, "expected A:B",
       render({"--sample-range", "0:99999999999999999999", "-o", "p.exr"})},
      {"RangeNegative", 2, "expected A:B", render({"--sample-range", "-1:5", "-o", "p.exr"})},
      {"RangeHalf", 2, "expected A:B", render({"--sample-range", "0:", "-o", "p.exr"})},
      {"RangeAndPart", 2, "not both",
       render({"--sample-range", "0:2", "--part", "0/2", "-o", "p.exr"})},
      {"TimeLimitNegative", 2, "--time-limit: must be a finite number",
       render({"--time-limit", "-1"})},
      {"TimeLimitInfinite", 2, "--time-limit: must be a finite number",
       render({"--time-limit", "inf"})},
      {"TargetErrorNan", 2, "--target-error: must be a finite number",
       render({"--target-error", "nan"})},
      {"MinSppOne", 2, "--min-spp", render({"--target-error", "0.1", "--min-spp", "1"})},
      {"SpheresZero", 2, "N must be a whole number", render({"--scene", "spheres:0"})},
      {"SpheresTooMany", 2, "N must be a whole number", render({"--scene", "spheres:1000000000"})},
      {"SpheresNegative", 2, "N must be a whole number", render({"--scene", "spheres:-5"})},
      {"UnknownScene", 2, "unknown scene", render({"--scene", "no\x1bscene"})},
      {"UnknownAccelerator", 2, "unknown accelerator 'magic'", render({"--accel", "magic"})},
      {"UnknownSampler", 2, "--sampler", render({"--sampler", "halton"})},
      {"UnknownFresnel", 2, "--fresnel", render({"--fresnel", "fast"})},
      {"SceneFileAndScene", 2, "not both", render({"scene.json", "--scene", "cover"})},
      {"UnknownOption", 2, "no-such-option", render({"--no-such-option"})},
      {"UnknownCommand", 2, "unknown command 'frobnicate'", {"frobnicate"}},
  };
}

std::vector<Case> output_cases() {
  return {
      {"OutputEmpty", 2, "-o/--output: the path is empty", render({"-o", ""})},
      {"OutputDot", 2, "names a directory", render({"-o", "."})},
      {"OutputDotDot", 2, "names a directory", render({"-o", ".."})},
      {"OutputDirectory", 2, "is a directory", render({"-o", "adir.png"})},
      {"OutputTrailingSlash", 2, "names a directory", render({"-o", "adir/"})},
      {"OutputMissingDirectory", 2, "does not exist", render({"-o", "nowhere/x.png"})},
      {"OutputDirectoryIsAFile", 2, "does not exist", render({"-o", "keep.png/x.png"})},
      {"OutputNullPseudoFormat", 2, "not an image format rtiow writes", render({"-o", "x.null"})},
      {"OutputTermPseudoFormat", 2, "not an image format rtiow writes", render({"-o", "x.term"})},
      {"OutputNoExtension", 2, "not an image format", render({"-o", "image"})},
      {"OutputUnknownFormat", 2, "not an image format", render({"-o", "x.docx"})},
      {"OutputFifo", 2, "is not a regular file", render({"-o", "fifo.png"})},
      {"OutputIsTheSceneFile",
       2,
       "is the input file",
       render({"scene.png", "-o", "scene.png"}),
       {{"scene.png", kScene}}},
      {"OutputIsTheSceneSpeltOtherwise",
       2,
       "is the input file",
       render({"scene.png", "-o", "./adir.png/../scene.png"}),
       {{"scene.png", kScene}}},
      {"OutputIsTheSceneThroughALink",
       2,
       "is the input file",
       render({"scene.png", "-o", "alias.png"}),
       {{"scene.png", kScene}}},
      {"DefaultOutputIsTheSceneFile",
       2,
       "is the input file",
       render({"noname.png"}),
       {{"noname.png", scene_with("\"name\": \"user scene\",", "")}}},
      {"OutputNameTooLong", 2, "the file name is longer than 200 bytes",
       render({"-o", std::string(300, 'a') + ".png"})},
      {"OutputPathTooLong", 2, "the path is longer than 3000 bytes",
       render({"-o",
               [] {
                 std::string path;  // short names, a long path: the path's rule is named
                 for (int i = 0; i < 300; ++i) path += "d123456789/";
                 return path + "x.png";
               }()})},
      {"OutputNewlineInMissingDirectory", 2, "does not exist",
       render({"-o", "new\nline/\x1b[31mred.png"})},
      {"StatsChannelsOnPng", 2, "must be .exr", render({"--stats-channels", "-o", "x.png"})},
      {"StatsChannelsOnHdr", 2, "must be .exr", render({"--stats-channels", "-o", "x.hdr"})},
      {"SceneOutputEmpty", 2, "the path is empty", {"scene", "cover", "-o", ""}},
      {"SceneOutputDirectory", 2, "is a directory", {"scene", "cover", "-o", "adir.png"}},
      {"SceneOutputMissingDirectory", 2, "does not exist", {"scene", "cover", "-o", "no/x.json"}},
      {"MergeOutputIsAPart",
       2,
       "is the input file",
       {"merge", "part0.exr", "part1.exr", "-o", "part0.exr"}},
      {"MergeOutputIsAPartThroughALink",
       2,
       "is the input file",
       {"merge", "part0.exr", "part1.exr", "-o", "part-alias.exr"}},
      {"MergeOutputPseudoFormat",
       2,
       "not an image format",
       {"merge", "part0.exr", "part1.exr", "-o", "x.null"}},
      {"MergeOutputEmpty", 2, "the path is empty", {"merge", "part0.exr", "part1.exr", "-o", ""}},
      {"BenchOutIsAFile",
       2,
       "--out 'keep.png': is not a directory",
       {"bench", "--out", "keep.png"}},
      {"BenchOutHoldsADirectoryForItsFigures",
       2,
       "is a directory",
       {"bench", "--out", "bench-dir-clash"}},
      {"AccuracyOutIsAFile",
       2,
       "--out 'keep.png': is not a directory",
       {"accuracy", "--out", "keep.png"}},
  };
}

std::vector<Case> part_cases() {
  const auto merge = [](std::vector<std::string> parts) {
    parts.insert(parts.begin(), "merge");
    parts.insert(parts.end(), {"-o", "merged.png"});
    return parts;
  };
  return {
      {"MergeMissingLastShare", 2, "samples [2, 4) of the job are missing", merge({"part0.exr"})},
      {"MergeMissingFirstShare", 2, "samples [0, 2) are missing", merge({"part1.exr"})},
      {"MergeSamePartTwice", 2, "overlap", merge({"part0.exr", "part0.exr"})},
      {"MergeSamePartThroughALink", 2, "overlap", merge({"part0.exr", "part-alias.exr"})},
      {"MergeDifferentRenders", 2, "a share of a different render",
       merge({"part0.exr", "other-render.exr"})},
      {"MergeAnotherVersionsShare", 2, "by rtiow 0.0.1: versions may draw other samples",
       merge({"older-version.exr", "part1.exr"})},
      {"MergeSceneFile", 2, "is not an image rtiow reads", merge({"scene.json"})},
      {"MergeUsersImage", 2, "is not an image rtiow reads", merge({"keep.png"})},
      {"MergePlainExr", 2, "not a part file", merge({"plain.exr"})},
      {"MergeTruncatedPart", 2, "part file 'truncated.exr'", merge({"truncated.exr", "part1.exr"})},
      {"MergeSamplesNotANumber", 2, "header field rtiow:part_samples is missing or not a whole",
       merge({"samples-not-a-number.exr", "part1.exr"})},
      {"MergeNegativeSamples", 2, "header field rtiow:part_samples",
       merge({"negative-samples.exr", "part1.exr"})},
      {"MergeZeroSamples", 2, "not a share of it", merge({"zero-samples.exr", "part1.exr"})},
      {"MergeOverflowingRange", 2, "not a share of it",
       merge({"overflowing-range.exr", "part1.exr"})},
      {"MergeHugeJob", 2, "not a share of it", merge({"huge-job.exr", "part1.exr"})},
      {"MergePassesNotAList", 2, "rtiow:passes is not a list of passes",
       merge({"passes-garbage.exr", "part1.exr"})},
      {"MergePassesWithoutTheirSums", 2, "records passes depth but holds no sums of them",
       merge({"passes-without-sums.exr", "part1.exr"})},
      // Each crafted sum is refused by the checks a checkpoint's get, naming the pixel and
      // the channel (core/film/sum_validation.h).
      {"MergeCraftedSum", 2, "pixel (0, 0) has sums no samples can add up to: squares.R is less",
       merge({"sum-word.exr", "part1.exr"})},
      {"MergeCraftedSquares", 2, "squares.G is beyond what 2 samples can add up to",
       merge({"square-words.exr", "part1.exr"})},
      {"MergeCraftedReplicateSum", 2, "odd.B is beyond what 1 sample of odd index",
       merge({"odd-word.exr", "part1.exr"})},
      {"MergeReplicateAboveItsSum", 2, "odd.G is more than sum.G",
       merge({"odd-above-sum.exr", "part1.exr"})},
      {"MergeCraftedCount", 2, "beyond what 0 samples of odd index",
       merge({"count-word.exr", "part1.exr"})},
      {"MergeCraftedFirstHitSum", 2, "first_hit.albedo.R is beyond what 2 samples",
       merge({"first-hit-word.exr", "part1.exr"})},
      {"MergeCraftedNormals", 2, "first_hit.N is longer than 2 samples of unit normals",
       merge({"normal-words.exr", "part1.exr"})},
      {"MergeWithoutJobField", 2, "header field rtiow:part_job_samples",
       merge({"no-job.exr", "part1.exr"})},
      {"MergeDirectory", 2, "is a directory", merge({"adir.png"})},
      {"MergeFifo", 2, "is not a regular file", merge({"fifo.png"})},
      {"MergeDevice", 2, "is not a regular file", merge({"/dev/zero"})},
      {"MergeMissingFile", 2, "No such file", merge({"part0.exr", "nothere.exr"})},
      {"MergeNothing", 2, "parts is required", {"merge", "-o", "merged.png"}},
      // A header's size is checked against the file's before any pixel is allocated (the
      // battery runs under a 4 GiB address-space limit: an allocation would end in exit 1).
      {"MergePartHeaderClaimsHugeSize", 2, "part file 'huge-header.exr'",
       merge({"huge-header.exr"})},
      {"DiffHeaderClaimsHugeSize",
       4,  // diff's "could not compare" (2 is its FAILURE)
       "more than a file of",
       {"diff", "huge-header.png", "part0.exr"}},
      {"LikeHeaderClaimsHugeSize", 2, "more than a file of",
       render({"--like", "huge-header.png", "-o", "again.png"})},
      // A file that is no image is refused from its first bytes, whatever its size (1 GiB of
      // zeros took minutes, as every image reader tried it).
      {"DiffZeros", 4, "is not an image rtiow reads", {"diff", "zeros.png", "part0.exr"}},
      {"MergeZeros", 2, "is not an image rtiow reads", merge({"zeros.exr"})},
      {"LikeZeros", 2, "is not an image rtiow reads",
       render({"--like", "zeros.png", "-o", "again.png"})},
  };
}

std::vector<Case> file_cases() {
  return {
      {"SceneIsADirectory", 2, "is a directory, not a file", render({"adir.png"})},
      {"SceneIsAFifo", 2, "is not a regular file", render({"fifo.png"})},
      {"SceneIsDevZero", 2, "is not a regular file", render({"/dev/zero"})},
      {"SceneIsDevNull", 2, "is not a regular file", render({"/dev/null"})},
      {"SceneIsMissing", 2, "No such file", render({"nothere.json"})},
      {"SceneIsHuge", 2, "more than the limit of 2048 MiB", render({"huge.json"})},
      {"SceneIsAnImage", 2, "is not a scene file", render({"keep.png"})},
      {"SceneIsProcFile", 2, "is not a scene file", render({"/proc/self/status"})},
  };
}

std::vector<Case> machine_cases() {
  return {
      {"OutOfMemoryBuildingTheScene",
       1,
       "rtiow: error:",
       render({"--scene", "spheres:60000000", "--width", "8", "--spp", "1", "-o", "x.png"}),
       {},
       {"--as=1500000000"}},
      {"DiskFullKeepsTheUsersPng",
       1,
       "cannot write 'keep.png': File too large",
       render({"--width", "200", "--spp", "1", "-o", "keep.png"}),
       {},
       {"--fsize=3000"}},
      {"DiskFullKeepsTheUsersExr",
       1,
       "cannot write 'keep.exr'",
       render({"--width", "200", "--spp", "1", "-o", "keep.exr"}),
       {},
       {"--fsize=3000"}},
      {"DiskFullKeepsThePartsMerge",
       1,
       "cannot write",
       {"merge", "part0.exr", "part1.exr", "-o", "keep.exr"},
       {},
       {"--fsize=300"}},
      {"StandardOutputFull",
       1,
       "cannot write to standard output",
       {"scene", "cover"},
       {},
       {},
       "/dev/full"},
  };
}

// A file-size limit under every other output format: the codecs encode in memory, so none
// of them (libjpeg calls exit(1) on a failed write) can end the process without a word or
// leave a temporary behind.
std::vector<Case> full_disk_format_cases() {
  std::vector<Case> cases;
  for (const char* ext : {"jpg", "ppm", "bmp", "tga", "tif", "hdr"}) {
    const std::string name = std::string("new.") + ext;
    std::string title = ext;
    title[0] = char(title[0] - 'a' + 'A');
    cases.push_back({"DiskFullUnder" + title + "WritesNothing",
                     1,
                     "cannot write '" + name + "': File too large",
                     render({"--width", "200", "--spp", "1", "-o", name}),
                     {},
                     {"--fsize=3000"}});
  }
  return cases;
}

std::vector<Case> all_cases() {
  std::vector<Case> all;
  for (auto cases : {structure_cases(), number_cases(), size_cases(), output_cases(), part_cases(),
                     file_cases(), machine_cases(), full_disk_format_cases()}) {
    all.insert(all.end(), cases.begin(), cases.end());
  }
  return all;
}

// CTest lists each case by its name, not by the bytes of the struct.
void PrintTo(const Case& c, std::ostream* os) {
  *os << c.name;
}

class HostileInput : public ::testing::TestWithParam<Case> {};

// The user's directory: their scene, parts, an image and an EXR of their own, a FIFO, a
// directory named like an image, links, a sparse 3 GiB file.
fs::path make_users_directory(const Case& c) {
  const fs::path dir = fs::path(RTIOW_TEST_OUTPUT_DIR) / "hostile" / c.name;
  fs::remove_all(dir);
  fs::create_directories(dir / "adir.png");
  fs::create_directories(dir / "bench-dir-clash" / "bench.json");  // where bench writes a file
  const fs::path fixture = fixtures();
  for (const auto& entry : fs::directory_iterator(fixture)) {
    if (entry.path().extension() == ".exr" || entry.path().filename() == "huge-header.png")
      fs::copy_file(entry.path(), dir / entry.path().filename());
  }
  write_file(dir / "scene.json", kScene);
  write_file(dir / "keep.png", "the user's own picture, not to be touched");
  write_file(dir / "keep.exr", "the user's own EXR, not to be touched");
  for (const auto& [name, text] : c.files) write_file(dir / name, text);
  EXPECT_EQ(mkfifo((dir / "fifo.png").c_str(), 0644), 0);
  fs::create_symlink("part0.exr", dir / "part-alias.exr");
  if (fs::exists(dir / "scene.png")) fs::create_symlink("scene.png", dir / "alias.png");
  if (c.name.find("Zeros") != std::string::npos) {
    for (const char* name : {"zeros.png", "zeros.exr"}) {
      std::ofstream(dir / name).close();
      fs::resize_file(dir / name, std::uintmax_t(1) << 30);  // sparse: no disk used
    }
  }
  if (c.name == "SceneIsHuge") {
    std::ofstream(dir / "huge.json").close();
    fs::resize_file(dir / "huge.json", std::uintmax_t(3) << 30);  // sparse: no disk used
  }
  return dir;
}

TEST_P(HostileInput, RefusedInOneSafeLineAndNothingChanges) {
  const Case& c = GetParam();
  const fs::path dir = make_users_directory(c);
  const auto before = snapshot(dir);
  const fs::path logs = fs::path(RTIOW_TEST_OUTPUT_DIR) / "hostile";
  const std::string err = (logs / (c.name + ".stderr")).string();
  const std::string out =
      c.stdout_path.empty() ? (logs / (c.name + ".stdout")).string() : c.stdout_path;

  const int code = run_capped(dir, c.args, out, err, c.limits);

  const std::string text = slurp(err);
  EXPECT_EQ(code, c.exit_code) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << "one line expected:\n" << text;
  EXPECT_EQ(text.rfind("rtiow: error: ", 0), 0u) << text;
  EXPECT_FALSE(text.empty() || text.back() != '\n') << text;
  EXPECT_LE(text.size(), 700u) << "an error line must stay short";
  const bool printable =
      std::all_of(text.begin(), text.end() - (text.empty() ? 0 : 1),
                  [](char ch) { return static_cast<unsigned char>(ch) >= 0x20 && ch != 0x7f; });
  EXPECT_TRUE(printable) << "control characters reached the terminal: " << text;
  EXPECT_NE(text.find(c.needle), std::string::npos) << "expected '" << c.needle << "' in: " << text;
  EXPECT_EQ(snapshot(dir), before) << "the user's files changed";
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);  // the huge sparse file included
}

INSTANTIATE_TEST_SUITE_P(Battery, HostileInput, ::testing::ValuesIn(all_cases()),
                         [](const ::testing::TestParamInfo<Case>& param_info) {
                           return param_info.param.name;
                         });

// The default output name made from a hostile scene name is a safe name in the working
// directory: no path separators, no NUL, no climbing out.
TEST(HostileOutputName, SceneNameBecomesASafeFileName) {
  const fs::path dir = fs::path(RTIOW_TEST_OUTPUT_DIR) / "hostile" / "SafeDefaultName";
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_file(dir / "s.json", scene_with("\"user scene\"", "\"../../x/\\u0000evil\\nname/..\""));
  const int code = run_capped(dir, render({"s.json"}), (dir / ".." / "safe.stdout").string(),
                              (dir / ".." / "safe.stderr").string(), {});
  EXPECT_EQ(code, 0) << slurp(dir / ".." / "safe.stderr");
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  ASSERT_EQ(names.size(), 2u) << "the image and nothing else: a finished render keeps no state";
  EXPECT_EQ(names[0], "s.json");
  EXPECT_EQ(names[1], "x--evil-name-...png");
  EXPECT_FALSE(fs::exists(dir / ".." / ".." / "x"));
}

}  // namespace
