// A render's life from the command line: signals, a request of days, standard input, scene
// files, parts merged, time limits, the Fresnel choice.

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <spawn.h>
#include <sys/ioctl.h>
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
#include "core/session/progress_display.h"
#include "core/session/progress_status.h"
#include "tests/cli_helpers.h"

namespace {

using namespace rtiow::test::cli;

std::vector<std::string> long_render(const fs::path& out) {
  // --restart: each case leaves its stopped render's checkpoint, which the next discards.
  return {"render", "--scene", "cover",     "--width", "160",
          "--spp",  "1000000", "--restart", "-o",      out.string()};
}

// Every signal that ends a process by default keeps the work: Ctrl-C, kill, a closed
// terminal or SSH session (HUP), SIGQUIT and a batch system's CPU-time limit (XCPU).
TEST(Cli, InterruptWritesTheSamplesCompleted) {
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGXCPU}) {
    SCOPED_TRACE(strsignal(sig));
    const fs::path out = output_path("interrupted.exr");
    // The signal must land in the sample loop: on a loaded machine the BVH's build may still
    // be under way after the first wait (a stop there writes nothing, rightly, and says so),
    // so the render is started again with a longer wait.
    std::optional<BackgroundRender> started;
    int code = 0;
    for (const int wait_ms : {500, 2000, 6000}) {
      started.emplace(long_render(out));
      ASSERT_TRUE(started->wait_until_rendering());
      std::this_thread::sleep_for(std::chrono::milliseconds(wait_ms));
      started->signal(sig);
      code = started->wait(20.0);
      if (started->stderr_text().find("before the render began") == std::string::npos) break;
    }
    BackgroundRender& r = *started;
    EXPECT_EQ(code, 128 + sig) << r.stderr_text();
    EXPECT_NE(r.stderr_text().find("interrupted: wrote"), std::string::npos) << r.stderr_text();
    // stderr is no terminal here: no empty line, and no progress line after "stopping".
    const std::string text = r.stderr_text();
    EXPECT_EQ(text.find("\n\n"), std::string::npos) << text;
    EXPECT_NE(text.rfind("rtiow: stopping", 0) == 0 ? 0 : text.find("\nrtiow: stopping"),
              std::string::npos)
        << text;
    EXPECT_EQ(text.find("progress:", text.find("rtiow: stopping")), std::string::npos) << text;
    auto in = OIIO::ImageInput::open(out.string());
    ASSERT_TRUE(in) << "no partial image written";
    const OIIO::ImageSpec& spec = in->spec();
    const int spp = spec.get_int_attribute("rtiow:spp");
    EXPECT_GE(spp, 1);
    EXPECT_LT(spp, 1000000);
    EXPECT_EQ(spec.get_int_attribute("rtiow:spp_requested"), 1000000);
    EXPECT_FALSE(spec.get_string_attribute("rtiow:stopped").empty());
    std::vector<float> pixels(std::size_t(spec.width * spec.height * 3));
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, pixels.data()));
    double sum = 0;
    for (float v : pixels) {
      ASSERT_TRUE(std::isfinite(v));
      sum += v;
    }
    EXPECT_GT(sum / double(pixels.size()), 0.1) << "the partial image is not black";
  }
}

// A signal ignored when rtiow starts (nohup, a script's background job) stays ignored.
// On a terminal the live progress line fits the terminal's width: on a 40-column terminal it
// wrapped, and each \r then rewrote only its last row, leaving the rest as a flood (issue 70).
TEST(Cli, TheLiveProgressLineFitsANarrowTerminal) {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(::grantpt(master), 0);
  ASSERT_EQ(::unlockpt(master), 0);
  winsize size{};
  size.ws_col = 40, size.ws_row = 12;
  ASSERT_EQ(::ioctl(master, TIOCSWINSZ, &size), 0);
  const std::string terminal = ::ptsname(master);
  // Held open here, so the reader sees no end before rtiow has opened it too.
  const int held = ::open(terminal.c_str(), O_RDWR | O_NOCTTY);
  ASSERT_GE(held, 0);
  std::string shown;
  std::thread reader([&] {
    char buffer[4096];
    for (ssize_t n; (n = ::read(master, buffer, sizeof buffer)) > 0;) shown.append(buffer, n);
  });
  rtiow::test::Launch command;
  command.argv = {RTIOW_BINARY, "render", "--scene", "cover", "--width",
                  "200",        "--spp",  "64",      "-o",    output_path("narrow.png").string()};
  command.stderr_path = terminal;
  const int code = rtiow::test::launch(command);
  ::close(held);  // the reader now ends (EIO) once it has read all
  reader.join();
  ::close(master);
  ASSERT_EQ(code, 0) << shown;
  int live_lines = 0;
  for (std::size_t at = shown.find("\033[K"); at != std::string::npos;
       at = shown.find("\033[K", at + 1)) {
    const std::size_t start = at + 3;
    const std::size_t end = std::min(shown.find_first_of("\r\n", start), shown.size());
    const std::string line = shown.substr(start, end - start);
    EXPECT_LE(line.size(), 39u) << "a live line wider than the terminal: " << line;
    EXPECT_NE(line.find('%'), std::string::npos) << "the share goes first: " << line;
    ++live_lines;
  }
  EXPECT_GE(live_lines, 1) << "no live line on a terminal:\n" << shown;
  EXPECT_EQ(rtiow::fit_to_columns(" 37.5%  elapsed 12.0s  ETA 20.0s  14.2 Mrays/s", 32),
            " 37.5%  elapsed 12.0s  ETA 20.0s");
  EXPECT_EQ(rtiow::fit_to_columns("4.69e+06 samples  elapsed 1.0s", 10), "4.69e+06 s");
}

TEST(Cli, InheritedIgnoredSignalStaysIgnored) {
  const fs::path out = output_path("nohup.exr");
  BackgroundRender r(long_render(out), {SIGHUP});
  ASSERT_TRUE(r.wait_until_rendering());
  r.signal(SIGHUP);
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  int status = 0;
  EXPECT_EQ(waitpid(r.pid(), &status, WNOHANG), 0) << "SIGHUP ended a render that ignores it";
  EXPECT_EQ(r.stderr_text().find("stopping"), std::string::npos) << r.stderr_text();
  r.signal(SIGINT);
  EXPECT_EQ(r.wait(20.0), 128 + SIGINT) << r.stderr_text();
}

// A count that means days of work is accepted, but not silently: a note says how long and how
// to bound it; a render of ordinary length says nothing.
TEST(Cli, ARequestOfDaysSaysSoBeforeItStarts) {
  const fs::path out = output_path("days.png");
  BackgroundRender r({"render", "--scene", "cover", "--width", "160", "--spp", "2000000000", "-q",
                      "--checkpoint", "0", "-o", out.string()});
  ASSERT_TRUE(r.wait_until_rendering());
  r.signal(SIGINT);
  EXPECT_EQ(r.wait(20.0), 128 + SIGINT) << r.stderr_text();
  EXPECT_NE(r.stderr_text().find("rtiow: note: 2000000000 spp at 160x107"), std::string::npos)
      << r.stderr_text();
  EXPECT_NE(r.stderr_text().find("days on a 2-core machine"), std::string::npos);
  const CommandResult ordinary = run_rtiow("render -q --scene cover --width 32 --spp 2 -o " +
                                           output_path("ordinary.png").string());
  EXPECT_EQ(ordinary.stderr_text, "");
}

// `rtiow scene cover | rtiow render -`: a scene on standard input renders as its file does, and
// a bad one is refused naming standard input.
// Two renders' files are the same image with the same provenance, but for the scene file one
// was read from (rtiow:scene_file), which `with_file` names.
void expect_same_but_scene_file(const fs::path& with_file, const fs::path& without,
                                const std::string& scene_file) {
  auto a = OIIO::ImageInput::open(with_file.string()), b = OIIO::ImageInput::open(without.string());
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->spec().get_string_attribute("rtiow:scene_file"), scene_file);
  EXPECT_EQ(b->spec().find_attribute("rtiow:scene_file"), nullptr);
  const auto attributes = [](const OIIO::ImageSpec& spec) {
    std::vector<std::string> all;
    for (const auto& attribute : spec.extra_attribs) {
      if (attribute.name() != "rtiow:scene_file")
        all.push_back(attribute.name().string() + "=" + attribute.get_string());
    }
    return all;
  };
  EXPECT_EQ(attributes(a->spec()), attributes(b->spec()));
  std::vector<float> pa(std::size_t(a->spec().image_pixels() * a->spec().nchannels)), pb(pa.size());
  ASSERT_TRUE(a->read_image(0, 0, 0, -1, OIIO::TypeDesc::FLOAT, pa.data()));
  ASSERT_TRUE(b->read_image(0, 0, 0, -1, OIIO::TypeDesc::FLOAT, pb.data()));
  EXPECT_EQ(pa, pb);
}

TEST(Cli, SceneFromStandardInputRendersAsItsFile) {
  const fs::path scene = output_path("scene.json"), piped = output_path("piped.png"),
                 direct = output_path("direct.png"), bad = output_path("bad.json");
  ASSERT_EQ(run_rtiow("scene cover --scene-seed 3 -o " + scene.string()).exit_code, 0);
  const std::string common = " --width 48 --spp 2 --reproducible -q ";
  const CommandResult p =
      run_rtiow("render -" + common + "-o " + piped.string(), "", {}, scene.string());
  ASSERT_EQ(p.exit_code, 0) << p.stderr_text;
  ASSERT_EQ(
      run_rtiow("render --scene cover --scene-seed 3" + common + "-o " + direct.string()).exit_code,
      0);
  expect_same_but_scene_file(piped, direct, "-");
  {
    std::ofstream broken(bad);
    broken << "{\"version\": 1,";
  }
  const CommandResult b = run_rtiow("render -" + common + "-o " + output_path("bad.png").string(),
                                    "", {}, bad.string());
  EXPECT_EQ(b.exit_code, 2);
  EXPECT_EQ(b.stderr_text.rfind("rtiow: error: standard input: ", 0), 0u) << b.stderr_text;
}

// A plain diff of two seeds fails on their noise; it says which comparison tells noise from a
// change. A small local change says nothing of the kind.
TEST(Cli, PlainDiffOfTwoSeedsPointsToTheNoiseAwareModes) {
  const fs::path a = output_path("s3.png"), b = output_path("s4.png");
  const std::string common = "render -q --scene cover --width 48 --spp 4 ";
  ASSERT_EQ(run_rtiow(common + "--seed 3 -o " + a.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow(common + "--seed 4 -o " + b.string()).exit_code, 0);
  const CommandResult d = run_rtiow("diff " + a.string() + " " + b.string());
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_NE(d.stdout_text.find("--stats-channels"), std::string::npos) << d.stdout_text;
  EXPECT_NE(d.stdout_text.find("several renders"), std::string::npos) << d.stdout_text;
  const CommandResult explicit_plain =
      run_rtiow("diff --mode plain " + a.string() + " " + b.string());
  EXPECT_EQ(explicit_plain.stdout_text.find("note:"), std::string::npos)
      << "asked for plain: no advice";
}

TEST(Cli, SecondInterruptAbortsAndLeavesTheOldFileAlone) {
  const fs::path out = output_path("kept.png");
  {
    std::ofstream old(out, std::ios::binary);
    old << "the good image from before";
  }
  // Wide enough that the first pass (1 spp) outlasts both signals: the first must not get
  // to write before the second arrives.
  BackgroundRender r(
      {"render", "--scene", "cover", "--width", "3000", "--spp", "1000", "-o", out.string()});
  ASSERT_TRUE(r.wait_until_rendering());
  // Past the scene's set-up (the lock is taken before it ends): a first signal there stops
  // the command before the render, with nothing for the second to cut short.
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  r.signal(SIGINT);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  r.signal(SIGINT);
  EXPECT_EQ(r.wait(5.0), 128 + SIGINT) << r.stderr_text();
  EXPECT_NE(r.stderr_text().find("ended by signal 2"), std::string::npos) << r.stderr_text();
  EXPECT_EQ(slurp(out), "the good image from before");
}

TEST(Cli, RendersSceneFilesWithOverridesAndRefusesBadOnes) {
  const fs::path scene = output_path("scene.json");
  {
    std::ofstream out(scene);
    out << R"({"version": 1, "name": "file scene",
      "camera": {"lookfrom": [0, 0, 0], "lookat": [0, 0, -1], "vfov": 90},
      "image": {"width": 20, "height": 10, "spp": 2, "depth": 4},
      "materials": {"red": {"type": "lambertian", "albedo": [0.8, 0.1, 0.1]}},
      "spheres": [{"center": [0, 0, -1], "radius": 0.5, "material": "red"}]})";
  }
  const fs::path out = output_path("from_file.exr");
  const CommandResult r = run_rtiow("render " + scene.string() + " --spp 3 -q -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  auto in = OIIO::ImageInput::open(out.string());
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().width, 20) << "the file's width";
  EXPECT_EQ(in->spec().get_int_attribute("rtiow:spp"), 3) << "--spp overrides the file";
  EXPECT_EQ(in->spec().get_string_attribute("rtiow:scene"), "file scene");

  expect_refused(scene.string() + " --scene cover", "give a scene file or --scene, not both");
  {
    std::ofstream bad(scene);
    bad << R"({"version": 1, "spheres": []})";
  }
  expect_refused(scene.string(), scene.string() + ": /: missing field \"camera\"");
}

TEST(Cli, WrittenSceneFileRendersTheIdenticalFile) {
  const fs::path scene = output_path("cover7.json");
  ASSERT_EQ(run_rtiow("scene cover --scene-seed 7 -o " + scene.string()).exit_code, 0);
  const fs::path a = output_path("a.png"), b = output_path("b.png");
  const std::string common = " --width 48 --spp 2 --reproducible -q -o ";
  ASSERT_EQ(run_rtiow("render " + scene.string() + common + a.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow("render --scene cover --scene-seed 7" + common + b.string()).exit_code, 0);
  expect_same_but_scene_file(a, b, scene.string());
}

TEST(Cli, RefusesImagesTooLargeForMemoryBeforeAllocating) {
  expect_refused("--width 40000 --height 40000", "more than half of this machine's");
  expect_refused("--width 100000 --height 100000", "more than 2^31 pixels");
}

TEST(Cli, PartsMergeIntoTheIdenticalFileAndBadSetsAreRefused) {
  const std::string common = " --scene cover --width 64 --spp 12 --reproducible -q ";
  const fs::path whole = output_path("whole.png");
  ASSERT_EQ(run_rtiow("render" + common + "-o " + whole.string()).exit_code, 0);
  std::vector<fs::path> parts;
  for (int i = 0; i < 3; ++i) {
    parts.push_back(output_path("part" + std::to_string(i) + ".exr"));
    ASSERT_EQ(run_rtiow("render" + common + "--part " + std::to_string(i) + "/3 -o " +
                        parts.back().string())
                  .exit_code,
              0);
  }
  const fs::path merged = output_path("merged.png");
  // Given in any order.
  const CommandResult m = run_rtiow("merge " + parts[2].string() + " " + parts[0].string() + " " +
                                    parts[1].string() + " -o " + merged.string());
  ASSERT_EQ(m.exit_code, 0) << m.stderr_text;
  EXPECT_EQ(slurp(merged), slurp(whole)) << "merged parts differ from the single render";

  // The variances too: parts rendered with --stats-channels keep two replicates and their
  // exact spreads, so the merge writes the channels one render writes, bit for bit.
  const fs::path whole_stats = output_path("whole-stats.exr"),
                 merged_stats = output_path("merged-stats.exr");
  ASSERT_EQ(run_rtiow("render" + common + "--stats-channels -o " + whole_stats.string()).exit_code,
            0);
  std::vector<fs::path> stats_parts;
  for (int i = 0; i < 3; ++i) {
    stats_parts.push_back(output_path("stats-part" + std::to_string(i) + ".exr"));
    ASSERT_EQ(run_rtiow("render" + common + "--stats-channels --part " + std::to_string(i) +
                        "/3 -o " + stats_parts.back().string())
                  .exit_code,
              0);
  }
  const CommandResult ms = run_rtiow("merge --stats-channels " + stats_parts[1].string() + " " +
                                     stats_parts[2].string() + " " + stats_parts[0].string() +
                                     " -o " + merged_stats.string());
  ASSERT_EQ(ms.exit_code, 0) << ms.stderr_text;
  EXPECT_EQ(slurp(merged_stats), slurp(whole_stats)) << "the merged variances differ";
  const CommandResult png_stats = run_rtiow(
      "merge --stats-channels " + stats_parts[0].string() + " " + stats_parts[1].string() + " " +
      stats_parts[2].string() + " -o " + output_path("stats.png").string());
  EXPECT_EQ(png_stats.exit_code, 2);
  EXPECT_NE(png_stats.stderr_text.find("must be .exr"), std::string::npos) << png_stats.stderr_text;
  // Parts drawn from one sequence (no --stats-channels) keep no estimate: refused by name.
  const CommandResult plain_stats =
      run_rtiow("merge --stats-channels " + parts[0].string() + " " + parts[1].string() + " " +
                parts[2].string() + " -o " + output_path("plain-stats.exr").string());
  EXPECT_EQ(plain_stats.exit_code, 2);
  EXPECT_NE(plain_stats.stderr_text.find("render them with --stats-channels"), std::string::npos)
      << plain_stats.stderr_text;
  // One sequence and two replicates are other samples: their parts do not merge.
  const CommandResult mixed =
      run_rtiow("merge " + parts[0].string() + " " + stats_parts[1].string() + " " +
                stats_parts[2].string() + " -o " + output_path("mixed.exr").string());
  EXPECT_EQ(mixed.exit_code, 2) << mixed.stderr_text;

  const fs::path early = output_path("early.exr"), late = output_path("late.exr");
  ASSERT_EQ(run_rtiow("render" + common + "--sample-range 0:5 -o " + early.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow("render" + common + "--sample-range 3:12 -o " + late.string()).exit_code, 0);
  const fs::path out = output_path("refused.png");
  auto refused = [&](const std::string& files, const std::string& needle) {
    const CommandResult r = run_rtiow("merge " + files + " -o " + out.string());
    EXPECT_EQ(r.exit_code, 2) << files;
    EXPECT_NE(r.stderr_text.find(needle), std::string::npos) << r.stderr_text;
    EXPECT_FALSE(fs::exists(out));
  };
  refused(early.string() + " " + late.string(), "overlap: both hold samples [3, 5)");
  refused(parts[0].string() + " " + parts[2].string(), "samples [4, 8) are missing");
  refused(parts[1].string() + " " + parts[2].string(), "samples [0, 4) are missing");
  refused(whole.string(), "not a part file");
  const fs::path other = output_path("other.exr");
  ASSERT_EQ(run_rtiow("render" + common + "--seed 2 --part 0/3 -o " + other.string()).exit_code, 0);
  refused(other.string() + " " + parts[1].string() + " " + parts[2].string(),
          "share of a different render");
  // Without the roulette other paths end: the book's estimator's part is another render's.
  const fs::path book = output_path("book-part.exr");
  ASSERT_EQ(
      run_rtiow("render" + common + "--roulette off --part 0/3 -o " + book.string()).exit_code, 0);
  refused(book.string() + " " + parts[1].string() + " " + parts[2].string(),
          "share of a different render");
  expect_refused("--part 0/3", "must be .exr");  // expect_refused writes a .png
  const fs::path part_out = output_path("refused.exr");
  for (const auto& [args, needle] :
       {std::pair<std::string, std::string>{"--part 3/3", "need 0 <= i < n"},
        {"--sample-range 5:5", "need A < B"},
        {"--sample-range 1-5", "expected A:B"},
        {"--part 0/3 --sample-range 0:4", "not both"}}) {
    const CommandResult r = run_rtiow("render -q -o " + part_out.string() + " " + args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.stderr_text.find(needle), std::string::npos) << r.stderr_text;
    EXPECT_FALSE(fs::exists(part_out));
  }
}

// A time-limited render's file says how many samples it holds, and it does hold them: the
// same render with exactly that --spp and no limit gives the same file.
TEST(Cli, TimeLimitedRenderHoldsTheSamplesItsMetadataSays) {
  const fs::path limited = output_path("limited.exr"), exact = output_path("exact.exr");
  const std::string common = "render -q --scene materials --width 64 --reproducible ";
  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(run_rtiow(common + "--time-limit 1 -o " + limited.string()).exit_code, 0);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 10.0) << "the limit was not honoured";
  auto in = OIIO::ImageInput::open(limited.string());
  ASSERT_TRUE(in);
  const int spp = in->spec().get_int_attribute("rtiow:spp");
  EXPECT_GT(spp, 1);
  EXPECT_NE(in->spec().get_string_attribute("rtiow:stopped").find("time limit"), std::string::npos);
  ASSERT_EQ(run_rtiow(common + "--spp " + std::to_string(spp) + " -o " + exact.string()).exit_code,
            0);
  std::vector<float> a(64 * 36 * 3), b(64 * 36 * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, a.data()));
  auto other = OIIO::ImageInput::open(exact.string());
  ASSERT_TRUE(other && other->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, b.data()));
  EXPECT_EQ(a, b);
}

TEST(Cli, FresnelChoiceChangesGlassOnly) {
  const fs::path schlick = output_path("schlick.exr"), exact = output_path("exact.exr");
  const std::string common = "render -q --scene materials --width 48 --spp 16 --reproducible ";
  ASSERT_EQ(run_rtiow(common + "--fresnel schlick -o " + schlick.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow(common + "--fresnel exact -o " + exact.string()).exit_code, 0);
  EXPECT_NE(slurp(schlick), slurp(exact));
  expect_refused("--fresnel fancy", "fresnel");
  const fs::path wide = output_path("wide.png"), wide_exact = output_path("wide_exact.png");
  const std::string no_glass = "render -q --scene wide-angle --width 32 --spp 4 --reproducible ";
  ASSERT_EQ(run_rtiow(no_glass + "-o " + wide.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow(no_glass + "--fresnel exact -o " + wide_exact.string()).exit_code, 0);
  EXPECT_EQ(slurp(wide), slurp(wide_exact)) << "a scene without glass does not change";
}

}  // namespace
