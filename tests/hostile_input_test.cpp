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

#include "tests/hostile_cases.h"
#include "tests/launch.h"
#include "tests/test_files.h"

namespace {

namespace fs = std::filesystem;

using rtiow::test::slurp;

using rtiow::test::write_file;
using rtiow::test::hostile::all_cases;
using rtiow::test::hostile::Case;
using rtiow::test::hostile::kScene;
using rtiow::test::hostile::scene_with;

// Runs rtiow with `args` in `dir` under the caps (a memory cap by prlimit, killed after 120 s);
// stdout to `stdout_path`, stderr to `stderr_path`. Returns the exit code, or 128 + signal.
int run_capped(const fs::path& dir, const std::vector<std::string>& args,
               const std::string& stdout_path, const std::string& stderr_path,
               const std::vector<std::string>& extra_limits) {
  rtiow::test::Launch command;
  command.argv = {"prlimit", "--as=4294967296"};
  command.argv.insert(command.argv.end(), extra_limits.begin(), extra_limits.end());
  command.argv.insert(command.argv.end(), {"--", RTIOW_BINARY});
  command.argv.insert(command.argv.end(), args.begin(), args.end());
  command.directory = dir.string();
  command.stdout_path = stdout_path, command.stderr_path = stderr_path;
  command.timeout_seconds = 120;
  return rtiow::test::launch(command);
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
// A PNG whose header claims `width` x `height`, `padding` bytes of comment making the file
// larger (a 10000x10000 claim in 200 KB was read: its 286 MiB were under 2048 times the file).
std::string png_claiming(std::uint32_t width, std::uint32_t height, std::size_t padding = 0) {
  const std::string header =
      big_endian(width) + big_endian(height) + std::string("\x08\x02\0\0\0", 5);
  const std::string deflate("\x78\x01\x01\x01\x00\xfe\xff\x00\x00\x01\x00\x01", 12);
  const std::string comment =
      padding > 0 ? png_chunk("tEXt", std::string("Comment\0", 8) + std::string(padding, 'x')) : "";
  return std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", header) + comment +
         png_chunk("IDAT", deflate) + png_chunk("IEND", "");
}

fs::path fixtures() {
  // Named by version: a build tree keeps the fixtures of an older suite under another name.
  const fs::path dir = fs::path(RTIOW_TEST_OUTPUT_DIR) / "hostile-fixtures-9";
  if (fs::exists(dir / "complete")) return dir;
  const fs::path work =
      fs::path(RTIOW_TEST_OUTPUT_DIR) / ("hostile-fixtures." + std::to_string(getpid()));
  fs::remove_all(work);
  fs::create_directories(work);
  write_file(work / "scene.json", kScene);
  const auto render = [&](const std::string& args) {
    rtiow::test::Launch command;
    command.argv = rtiow::test::words(std::string(RTIOW_BINARY) + " render -q scene.json " + args);
    command.directory = work.string();
    EXPECT_EQ(rtiow::test::launch(command), 0) << args;
  };
  render("--part 0/2 -o part0.exr");
  render("--part 1/2 -o part1.exr");
  render("--seed 7 --part 1/2 -o other-render.exr");
  render("-o plain.exr");
  render("--part 0/2 --passes albedo,normal,depth -o passes0.exr");
  render("--part 0/2 --stats-channels -o stats0.exr");
  render("--part 1/2 --stats-channels -o stats1.exr");
  render("--part 0/2 --denoise -o denoise0.exr");
  render("--part 1/2 --denoise -o denoise1.exr");
  render("--part 1/2 --denoise --width 24 -o denoise-smaller1.exr");
  // Taller than the 64 rows a part is read by at a time (core/render/render_part.cpp).
  render("--part 0/2 --width 6 --height 150 -o tall0.exr");
  render("--part 1/2 --width 6 --height 150 -o tall1.exr");
  // Part files whose header or sums lie, written field by field and word by word: `edit`
  // changes the header, `words` the words (by channel name) of pixel `pixel` (row by row) of
  // the part `from`.
  using Words = std::function<void(std::function<std::uint32_t&(const std::string&)>)>;
  const auto crafted = [&](const std::string& name,
                           const std::function<void(OIIO::ImageSpec&)>& edit,
                           const std::string& from = "part0.exr", const Words& words = {},
                           std::size_t pixel = 0) {
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
        return data[pixel * std::size_t(spec.nchannels) + std::size_t(std::max(at, 0))];
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
  crafted(
      "tall-late-word.exr", same, "tall0.exr", [](auto word) { word("sum.G.3") = 0x10u; },
      130 * 6 + 5);
  crafted("odd-above-sum.exr", same, "part0.exr", [](auto word) {
    for (const char* w : {".0", ".1", ".2", ".3"})
      word(std::string("odd.G") + w) = word(std::string("sum.G") + w);
    word("odd.G.0") += 1;  // the sum's low word is far from 2^32 - 1 for a pixel of about 1
  });
  crafted("denoise-odd-above-sum.exr", same, "denoise0.exr", [](auto word) {
    for (const char* w : {".0", ".1", ".2", ".3"})
      word(std::string("odd.R") + w) = word(std::string("sum.R") + w);
    word("odd.R.0") += 1;
  });
  crafted("count-word.exr", [](auto& s) { s.attribute("rtiow:part_samples", "1"); });
  crafted(
      "replicates-seven.exr", [](auto& s) { s.attribute("rtiow:replicates", "7"); }, "stats0.exr");
  crafted("first-hit-word.exr", same, "passes0.exr",
          [](auto word) { word("first_hit.albedo.R.1") = 5; });
  crafted("normal-words.exr", same, "passes0.exr", [](auto word) {
    for (const char* axis : {"X", "Y", "Z"}) {  // each axis within its bound, together too long
      const std::string c = std::string("first_hit.N.") + axis;
      word(c + ".0") = 0, word(c + ".1") = 2, word(c + ".2") = 0, word(c + ".3") = 0;
    }
  });
  // Images whose description holds rtiow keys that no JSON reader may take: a key twice, a
  // nesting no description of rtiow's has.
  render("-o like.tif");
  const auto described = [&](const std::string& name,
                             const std::function<std::string(std::string)>& edit) {
    auto in = OIIO::ImageInput::open((work / "like.tif").string());
    ASSERT_TRUE(in);
    OIIO::ImageSpec spec = in->spec();
    std::vector<std::uint8_t> data(spec.image_bytes());
    ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, data.data()));
    const std::string description = spec.get_string_attribute("ImageDescription");
    ASSERT_NE(description.find("\"rtiow:seed\""), std::string::npos) << description;
    spec.attribute("ImageDescription", edit(description));
    auto out = OIIO::ImageOutput::create((work / name).string());
    ASSERT_TRUE(out && out->open((work / name).string(), spec) &&
                out->write_image(OIIO::TypeDesc::UINT8, data.data()) && out->close());
  };
  described("like-key-twice.tif",
            [](std::string d) { return d.insert(d.find("\"rtiow:seed\""), "\"rtiow:seed\":3,"); });
  described("like-too-deep.tif", [](std::string d) {
    return d.insert(1, "\"deep\":" + std::string(100, '[') + std::string(100, ']') + ",");
  });
  const std::string part = slurp(work / "part0.exr");
  write_file(work / "truncated.exr", part.substr(0, part.size() / 2));
  // Headers that claim far more pixels than their files hold: a part of 8192x8192 (10 GB of
  // sums) and a 30000x30000 PNG, each a few KB.
  write_file(work / "huge-header.exr", with_box(with_box(part, "dataWindow"), "displayWindow"));
  write_file(work / "huge-header.png", png_claiming(30000, 30000));
  write_file(work / "beyond-deflate.png", png_claiming(10000, 10000, 200000));
  write_file(work / "complete", "");
  std::error_code ignored;
  fs::rename(work, dir, ignored);  // another process may have won: its files are the same
  if (ignored) fs::remove_all(work);
  return dir;
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
    const fs::path extension = entry.path().extension();
    if (extension == ".exr" || extension == ".png" || extension == ".tif")
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
  const int code =
      run_capped(dir, {"render", "-q", "s.json"}, (dir / ".." / "safe.stdout").string(),
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
