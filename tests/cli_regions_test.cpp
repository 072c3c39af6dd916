// What a render writes beyond its image and where it shows it: a crop of the frame, the
// albedo, normal and depth passes, and the render shown in tev as it goes.

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/rtiow.h"
#include "core/session/progress_status.h"
#include "tests/cli_helpers.h"
#include "tests/fake_viewer.h"

namespace {

using namespace rtiow::test::cli;
using rtiow::test::bound_loopback_socket;
using rtiow::test::FakeTev;

// The region X0,Y0,X1,Y1 of an image of `width` floats a pixel (RGB).
std::vector<float> region_of(const std::vector<float>& rgb, int width, int x0, int y0, int x1,
                             int y1) {
  std::vector<float> region;
  for (int y = y0; y < y1; ++y) {
    const auto row = rgb.begin() + std::ptrdiff_t((std::size_t(y) * std::size_t(width)) * 3);
    region.insert(region.end(), row + x0 * 3, row + x1 * 3);
  }
  return region;
}

// --crop renders the whole image's pixels in its region, bit for bit: into EXR (which keeps
// the region's place in the frame) and PNG (the region alone), by parts merged, resumed from
// a kept checkpoint, and again with --like; a region outside the image and an adaptive crop
// are refused before any work.
TEST(Cli, ACropRendersTheWholeImagesPixelsInEveryWayARenderIsMade) {
  const fs::path dir = empty_output_dir("crop");
  const auto at = [&](const std::string& name) { return (dir / name).string(); };
  const std::string base = "render -q --scene cover --width 64 --spp 6 --reproducible ";
  const std::string crop = " --crop 10,5,40,27";
  ASSERT_EQ(run_rtiow(base + "-o " + at("full.exr")).exit_code, 0);
  ASSERT_EQ(run_rtiow(base + "-o " + at("full.png")).exit_code, 0);
  CommandResult r = run_rtiow(base + crop + " -o " + at("crop.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  int width = 0, height = 0, w = 0, h = 0;
  const std::vector<float> full = exr_pixels(at("full.exr"), width, height);
  const std::vector<float> expected = region_of(full, width, 10, 5, 40, 27);
  EXPECT_EQ(exr_pixels(at("crop.exr"), w, h), expected) << "the crop's pixels are not the image's";
  EXPECT_EQ(w, 30);
  EXPECT_EQ(h, 22);
  {
    auto in = OIIO::ImageInput::open(at("crop.exr"));
    ASSERT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.x, 10);
    EXPECT_EQ(spec.y, 5);
    EXPECT_EQ(spec.full_width, 64);
    EXPECT_EQ(spec.full_height, 43);
    EXPECT_EQ(spec.get_string_attribute("rtiow:crop"), "10,5,40,27");
    EXPECT_EQ(spec.get_string_attribute("rtiow:frame"), "64x43");
  }
  // PNG: the region alone, its bytes the whole PNG's there.
  ASSERT_EQ(run_rtiow(base + crop + " -o " + at("crop.png")).exit_code, 0);
  {
    OIIO::ImageBuf whole(at("full.png")), region(at("crop.png"));
    ASSERT_TRUE(whole.read() && region.read());
    EXPECT_EQ(region.spec().width, 30);
    EXPECT_EQ(region.spec().x, 0);
    std::vector<unsigned char> a(30 * 22 * 3), b(30 * 22 * 3);
    whole.get_pixels(OIIO::ROI(10, 40, 5, 27, 0, 1, 0, 3), OIIO::TypeDesc::UINT8, a.data());
    region.get_pixels(OIIO::ROI(0, 30, 0, 22, 0, 1, 0, 3), OIIO::TypeDesc::UINT8, b.data());
    EXPECT_EQ(a, b);
  }
  // Two parts of the crop, merged: the crop's file, byte for byte.
  for (const char* part : {"0/2", "1/2"}) {
    r = run_rtiow(base + crop + " --part " + part + " -o " +
                  at(std::string("part") + part[0] + ".exr"));
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  }
  r = run_rtiow("merge -q " + at("part0.exr") + " " + at("part1.exr") + " -o " + at("merged.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(slurp(at("merged.exr")), slurp(at("crop.exr"))) << "merged parts differ";
  // A part of another region does not merge with these.
  ASSERT_EQ(run_rtiow(base + " --crop 10,5,40,28 --part 1/2 -o " + at("other.exr")).exit_code, 0);
  r = run_rtiow("merge -q " + at("part0.exr") + " " + at("other.exr") + " -o " + at("no.exr"));
  EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
  EXPECT_FALSE(fs::exists(at("no.exr")));
  // Refined from a kept checkpoint: 3 spp kept, resumed to 6.
  const std::string resumable = "render -q --scene cover --width 64 --reproducible" + crop;
  ASSERT_EQ(run_rtiow(resumable + " --spp 3 --keep-state -o " + at("resumed.exr")).exit_code, 0);
  r = run_rtiow(resumable + " --spp 6 --resume -o " + at("resumed.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(slurp(at("resumed.exr")), slurp(at("crop.exr"))) << "the resumed crop differs";
  // Again from the image's own record.
  r = run_rtiow("render -q --like " + at("crop.exr") + " -o " + at("like.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(slurp(at("like.exr")), slurp(at("crop.exr"))) << "--like lost the crop";
  // Another frame size drops the region only when told which (it was dropped silently).
  r = run_rtiow("render -q --like " + at("crop.exr") + " --width 32 -o " + at("wider.exr"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("is the region "), std::string::npos) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("give --crop too (--crop 0,0,W,H for the whole frame)"),
            std::string::npos)
      << r.stderr_text;
  EXPECT_FALSE(fs::exists(at("wider.exr")));
  r = run_rtiow("render -q --like " + at("crop.exr") + " --width 32 --crop 0,0,32,21 -o " +
                at("wider.exr"));
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;

  r = run_rtiow(base + " --crop 10,5,70,27 -o " + at("outside.png"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("crop 10,5,70,27 is not a region of the 64x43 image"),
            std::string::npos)
      << r.stderr_text;
  r = run_rtiow("render -q --scene cover --width 64 --target-error 0.1 --crop 0,0,8,8 -o " +
                at("adaptive.png"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("uniform sampling only"), std::string::npos) << r.stderr_text;
  EXPECT_FALSE(fs::exists(at("outside.png")) || fs::exists(at("adaptive.png")));
}

// --passes: the albedo, normal and depth channels beside an EXR's image, which they leave as it
// was; merged from parts, resumed from a checkpoint and repeated with --like to the same bytes
// as one render; refused where no channel fits, and a checkpoint without them is not resumed.
// A crop costs its region, not the frame (issue 69): a 16x16 crop of a 40000x40000 frame, which
// no machine here could hold whole, renders; and crops that tile a frame, each an .exr whose data
// window is its region, assemble with oiiotool (docs/usage.md) into the whole render's pixels.
TEST(Cli, CropsOfAnyFrameTileItAndAssembleIntoTheWholeRender) {
  const fs::path dir = empty_output_dir(test_name());
  CommandResult r = run_rtiow(
      "render -q --scene cover --width 40000 --height 40000 --crop 20000,20000,20016,20016 --spp 2 "
      "-o " +
      (dir / "far.exr").string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  int width = 0, height = 0;
  EXPECT_EQ(exr_pixels(dir / "far.exr", width, height).size(), 16u * 16u * 3u);
  // The whole frame, and three crops that tile it.
  r = run_rtiow("render -q --scene cover --width 64 --spp 4 --passes depth -o " +
                (dir / "whole.exr").string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  std::vector<std::string> assemble = {"/usr/bin/oiiotool"};
  for (const std::string crop : {"0,0,64,20", "0,20,30,43", "30,20,64,43"}) {
    const fs::path part = dir / ("crop-" + crop + ".exr");
    r = run_rtiow("render -q --scene cover --width 64 --spp 4 --passes depth --crop " + crop +
                  " -o " + part.string());
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    assemble.push_back(part.string());
    if (assemble.size() > 2) assemble.push_back("--add");
  }
  assemble.insert(assemble.end(), {"-o", (dir / "assembled.exr").string()});
  rtiow::test::Launch oiiotool;
  oiiotool.argv = assemble;
  ASSERT_EQ(rtiow::test::launch(oiiotool), 0);
  int w = 0, h = 0;
  EXPECT_EQ(exr_pixels(dir / "assembled.exr", w, h), exr_pixels(dir / "whole.exr", width, height));
  EXPECT_EQ(w, 64);
  EXPECT_EQ(h, 43);
  EXPECT_EQ(exr_channel(dir / "assembled.exr", "Z"), exr_channel(dir / "whole.exr", "Z"));
}

TEST(Cli, PassesAreWrittenBesideTheImageAndCombineLikeIt) {
  const fs::path dir = empty_output_dir("passes");
  const auto at = [&](const std::string& name) { return (dir / name).string(); };
  const std::string base = "render -q --scene cover --width 64 --reproducible ";
  const std::string passes = " --passes albedo,normal,depth";
  CommandResult r = run_rtiow(base + "--spp 6" + passes + " -o " + at("full.exr") +
                              " --summary-json " + at("summary.json"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  ASSERT_EQ(run_rtiow(base + "--spp 6 -o " + at("plain.exr")).exit_code, 0);
  int width = 0, height = 0, w = 0, h = 0;
  EXPECT_EQ(exr_pixels(at("full.exr"), width, height), exr_pixels(at("plain.exr"), w, h))
      << "the passes changed the image";
  {
    auto in = OIIO::ImageInput::open(at("full.exr"));
    ASSERT_TRUE(in);
    std::vector<std::string> names = in->spec().channelnames;
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"B", "G", "N.X", "N.Y", "N.Z", "R", "Z", "albedo.B",
                                               "albedo.G", "albedo.R"}));
    EXPECT_EQ(in->spec().get_string_attribute("rtiow:passes"), "albedo,normal,depth");
  }
  // The cover's top-left pixel is sky: all 0; much of its bottom row sees only the ground: its
  // albedo of 0.5, the normal +y, and a distance.
  const std::vector<float> depth = exr_channel(at("full.exr"), "Z");
  const std::vector<float> ny = exr_channel(at("full.exr"), "N.Y");
  const std::vector<float> albedo = exr_channel(at("full.exr"), "albedo.G");
  ASSERT_EQ(depth.size(), std::size_t(width * height));
  EXPECT_EQ(depth[0], 0.0f);
  EXPECT_EQ(ny[0], 0.0f);
  EXPECT_EQ(albedo[0], 0.0f);
  int ground = 0;
  for (int x = 0; x < width; ++x) {
    const std::size_t p = std::size_t((height - 1) * width + x);
    if (albedo[p] == 0.5f && ny[p] > 0.9999f && depth[p] > 1.0f) ++ground;
  }
  EXPECT_GT(ground, width / 3);
  const auto summary = nlohmann::json::parse(slurp(at("summary.json")));
  EXPECT_EQ(summary["passes"], nlohmann::json({"albedo", "normal", "depth"}));

  // Two parts, merged: the one render's file, byte for byte.
  for (const char* part : {"0/2", "1/2"}) {
    r = run_rtiow(base + "--spp 6" + passes + " --part " + part + " -o " +
                  at(std::string("part") + part[0] + ".exr"));
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  }
  r = run_rtiow("merge -q " + at("part0.exr") + " " + at("part1.exr") + " -o " + at("merged.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(slurp(at("merged.exr")), slurp(at("full.exr"))) << "merged parts differ";
  // A part without the passes does not merge with one that has them.
  ASSERT_EQ(run_rtiow(base + "--spp 6 --part 1/2 -o " + at("bare.exr")).exit_code, 0);
  r = run_rtiow("merge -q " + at("part0.exr") + " " + at("bare.exr") + " -o " + at("no.exr"));
  EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("with the same passes"), std::string::npos) << r.stderr_text;
  EXPECT_FALSE(fs::exists(at("no.exr")));

  // Resumed from a kept checkpoint: 3 spp kept, refined to 6.
  ASSERT_EQ(
      run_rtiow(base + "--spp 3 --keep-state" + passes + " -o " + at("resumed.exr")).exit_code, 0);
  r = run_rtiow(base + "--spp 6 --resume" + passes + " -o " + at("resumed.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(slurp(at("resumed.exr")), slurp(at("full.exr"))) << "the resumed passes differ";
  // A checkpoint kept without the passes has no sums for them: refused by name.
  ASSERT_EQ(run_rtiow(base + "--spp 3 --keep-state -o " + at("bare_state.exr")).exit_code, 0);
  r = run_rtiow(base + "--spp 6 --resume" + passes + " -o " + at("bare_state.exr"));
  EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("passes: the checkpoint's 'none'"), std::string::npos)
      << r.stderr_text;

  // Again from the image's own record; into a PNG, which holds no passes, the image alone.
  r = run_rtiow("render -q --like " + at("full.exr") + " -o " + at("like.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(slurp(at("like.exr")), slurp(at("full.exr"))) << "--like lost the passes";
  r = run_rtiow("render -q --like " + at("full.exr") + " -o " + at("like.png"));
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;

  // Refused before any work: a format without channels, an unknown pass.
  r = run_rtiow(base + "--spp 1" + passes + " -o " + at("passes.png"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("--passes: output"), std::string::npos) << r.stderr_text;
  r = run_rtiow(base + "--spp 1 --passes albedo,depht -o " + at("typo.exr"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("unknown pass 'depht'; did you mean depth?"), std::string::npos)
      << r.stderr_text;
  EXPECT_FALSE(fs::exists(at("passes.png")) || fs::exists(at("typo.exr")));
}

// tev's packets, read as tev reads them: a 32-bit little-endian size (itself included), the
// type, the fields.
class TevReader {
 public:
  explicit TevReader(std::string_view bytes) : bytes_(bytes) {}
  bool next_packet() {
    at_ = end_;
    if (at_ + 5 > bytes_.size()) return false;
    end_ = at_ + std::size_t(integer<std::uint32_t>());
    if (end_ > bytes_.size() || end_ < at_ + 5) return false;
    type_ = bytes_[at_++];
    return true;
  }
  char type() const { return type_; }
  template <typename Int>
  Int integer() {
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < sizeof(Int); ++i) {
      value |= std::uint64_t(static_cast<unsigned char>(bytes_[at_ + i])) << (8 * i);
    }
    at_ += sizeof(Int);
    return static_cast<Int>(value);
  }
  float number() {
    const auto bits = integer<std::uint32_t>();
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  std::string text() {
    const std::size_t zero = bytes_.find('\0', at_);
    std::string value(bytes_.substr(at_, zero - at_));
    at_ = zero + 1;
    return value;
  }
  bool at_end() const { return at_ == end_; }

 private:
  std::string_view bytes_;
  std::size_t at_ = 0, end_ = 0;
  char type_ = 0;
};

// What a viewer shows after every packet: the image tev made (CreateImage) with each update
// (UpdateImageV3, RGB interleaved) pasted in at its place.
struct ShownImage {
  std::string name;
  int width = 0, height = 0, updates = 0;
  std::vector<std::string> channels;
  std::vector<float> rgb;
  std::vector<std::vector<float>> extra;  // the channels after R, G, B, one float a pixel
  std::vector<std::pair<int, int>> update_places;
  std::string problem;  // "" when every packet was as tev expects
};

ShownImage replay_tev(const std::string& bytes) {
  ShownImage shown;
  TevReader in(bytes);
  while (in.next_packet()) {
    if (in.type() == 4) {  // CreateImage
      in.integer<std::uint8_t>();
      shown.name = in.text();
      shown.width = in.integer<std::int32_t>(), shown.height = in.integer<std::int32_t>();
      const int channels = in.integer<std::int32_t>();
      for (int c = 0; c < channels; ++c) shown.channels.push_back(in.text());
      if (channels < 3 || shown.channels[0] != "R" || shown.channels[1] != "G" ||
          shown.channels[2] != "B") {
        shown.problem = "an image whose first channels are not R, G, B";
        return shown;
      }
      const std::size_t pixels = std::size_t(shown.width) * std::size_t(shown.height);
      shown.rgb.assign(pixels * 3, -1.0f);
      shown.extra.assign(std::size_t(channels - 3), std::vector<float>(pixels, -1.0f));
    } else if (in.type() == 6) {  // UpdateImageV3
      in.integer<std::uint8_t>();
      if (in.text() != shown.name) shown.problem = "an update of another image";
      const int channels = in.integer<std::int32_t>();
      std::vector<std::string> names;
      for (int c = 0; c < channels; ++c) names.push_back(in.text());
      const int x = in.integer<std::int32_t>(), y = in.integer<std::int32_t>();
      const int w = in.integer<std::int32_t>(), h = in.integer<std::int32_t>();
      std::vector<std::int64_t> offsets(std::size_t(std::max(channels, 0)));
      std::vector<std::int64_t> strides(offsets.size());
      for (auto& o : offsets) o = in.integer<std::int64_t>();
      for (auto& s : strides) s = in.integer<std::int64_t>();
      bool interleaved = names == shown.channels;
      for (std::size_t c = 0; interleaved && c < offsets.size(); ++c) {
        interleaved = offsets[c] == std::int64_t(c) && strides[c] == channels;
      }
      if (!interleaved || x < 0 || y < 0 || x + w > shown.width || y + h > shown.height) {
        shown.problem = "an update outside the image, or not of its channels interleaved";
        return shown;
      }
      for (int row = 0; row < h; ++row) {
        for (int col = 0; col < w; ++col) {
          const std::size_t p =
              std::size_t(y + row) * std::size_t(shown.width) + std::size_t(x + col);
          for (int c = 0; c < channels; ++c) {
            const float v = in.number();
            if (c < 3) {
              shown.rgb[p * 3 + std::size_t(c)] = v;
            } else {
              shown.extra[std::size_t(c - 3)][p] = v;
            }
          }
        }
      }
      ++shown.updates;
      shown.update_places.emplace_back(x, y);
    } else {
      shown.problem = "a packet of type " + std::to_string(int(in.type()));
    }
    if (!in.at_end()) shown.problem = "a packet of another size than its fields";
  }
  return shown;
}

// --display: tev gets the image created at the frame's size, then its pixels as the render
// goes, the last of them the file's; a crop shows in its place; a viewer that is not there is
// a warning and the render is whole; a bad address is refused before any work.
TEST(Cli, DisplayShowsTheRenderInTevAsItGoes) {
  const fs::path out = output_path("displayed.exr");
  {
    FakeTev tev;
    ASSERT_GT(tev.port(), 0);
    const CommandResult r = run_rtiow(
        "render -q --scene cover --width 48 --spp 64 --reproducible --preview 0.001 "
        "--passes normal,depth --display 127.0.0.1:" +
        std::to_string(tev.port()) + " -o " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    EXPECT_EQ(r.stderr_text, "");
    const ShownImage shown = replay_tev(tev.received());
    EXPECT_EQ(shown.problem, "");
    EXPECT_EQ(shown.name, out.filename().string());
    EXPECT_EQ(shown.width, 48);
    EXPECT_EQ(shown.height, 32);
    EXPECT_GE(shown.updates, 1);
    int width = 0, height = 0;
    EXPECT_EQ(shown.rgb, exr_pixels(out, width, height)) << "tev shows other pixels than the file";
    // The passes as more channels, their values the file's.
    ASSERT_EQ(shown.channels, (std::vector<std::string>{"R", "G", "B", "N.X", "N.Y", "N.Z", "Z"}));
    for (std::size_t c = 0; c < 4; ++c) {
      EXPECT_EQ(shown.extra[c], exr_channel(out, shown.channels[c + 3])) << shown.channels[c + 3];
    }
  }
  {
    FakeTev tev;
    const fs::path crop = output_path("displayed-crop.exr");
    const CommandResult r = run_rtiow(
        "render -q --scene cover --width 48 --spp 4 --crop 8,4,40,20 --display 127.0.0.1:" +
        std::to_string(tev.port()) + " -o " + crop.string());
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    const ShownImage shown = replay_tev(tev.received());
    EXPECT_EQ(shown.problem, "");
    EXPECT_EQ(shown.width, 48);
    ASSERT_FALSE(shown.update_places.empty());
    EXPECT_EQ(shown.update_places.back(), std::make_pair(8, 4));
  }
  // Nobody listening: the render is whole, with one warning.
  int port = 0;
  // A port that was free a moment ago, and is again once the probe closes.
  ::close(bound_loopback_socket(/*listen=*/false, port));
  ASSERT_GT(port, 0);
  const fs::path alone = output_path("displayed-alone.png");
  CommandResult r = run_rtiow("render -q --scene cover --width 16 --spp 2 --display 127.0.0.1:" +
                              std::to_string(port) + " -o " + alone.string());
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_TRUE(fs::exists(alone));
  EXPECT_NE(r.stderr_text.find("warning: --display '127.0.0.1:" + std::to_string(port) +
                               "': cannot connect"),
            std::string::npos)
      << r.stderr_text;
  r = run_rtiow("render -q --width 16 --spp 2 --display localhost:99999 -o " +
                output_path("never.png").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("--display 'localhost:99999': expected HOST:PORT"),
            std::string::npos)
      << r.stderr_text;
  EXPECT_FALSE(fs::exists(output_path("never.png")));
  // A port alone was read as the host 0.0.55.78 (issue 70).
  r = run_rtiow("render -q --width 16 --spp 2 --display 14158 -o " +
                output_path("never.png").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("--display '14158': a number alone is not a host"),
            std::string::npos)
      << r.stderr_text;
  EXPECT_FALSE(fs::exists(output_path("never.png")));
}

// With --denoise the file holds the denoised image, and so does the viewer's last picture (it
// ended on the noisy one, the denoiser's work unseen).
TEST(Cli, DisplayEndsOnTheDenoisedImageItWrites) {
  FakeTev tev;
  ASSERT_GT(tev.port(), 0);
  const fs::path out = output_path("displayed-denoised.exr");
  const CommandResult r =
      run_rtiow("render -q --scene cover --width 48 --spp 8 --denoise --display 127.0.0.1:" +
                std::to_string(tev.port()) + " -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const ShownImage shown = replay_tev(tev.received());
  EXPECT_EQ(shown.problem, "");
  EXPECT_GE(shown.updates, 2);
  int width = 0, height = 0;
  const std::vector<float> written = exr_pixels(out, width, height);
  ASSERT_FALSE(written.empty());
  EXPECT_EQ(shown.rgb, written) << "tev ends on other pixels than the file";
  // The file's image is the denoised one, not the noisy one beside it.
  const std::vector<float> noisy = exr_channel(out, "noisy.R");
  std::size_t differ = 0;
  for (std::size_t p = 0; p < noisy.size(); ++p) differ += written[3 * p] != noisy[p] ? 1 : 0;
  EXPECT_GT(differ, noisy.size() / 2);
}

}  // namespace
