// Commands as a user meets them: diff's verdicts and refusals, one-line errors that
// suggest what was meant, progress in every mode, a preview, unwritable outputs refused first.

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
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/rtiow.h"
#include "core/session/progress_status.h"
#include "core/session/work_display.h"
#include "tests/cli_helpers.h"

namespace {

using namespace rtiow::test::cli;

TEST(Cli, DiffPassesOtherSeedsFailsAMutationAndRefusesMismatches) {
  const std::string render =
      "render -q --scene cover --width 64 --height 36 --spp 16 --stats-channels ";
  const fs::path a = output_path("a.exr"), b = output_path("b.exr"), turned = output_path("t.exr"),
                 small = output_path("s.exr");
  ASSERT_EQ(run_rtiow(render + "--seed 3 -o " + a.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow(render + "--seed 4 -o " + b.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow(render + "--seed 4 --lookat 0.236,0,0 -o " + turned.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow("render -q --scene cover --width 32 --height 18 --spp 4 -o " + small.string())
                .exit_code,
            0);
  const CommandResult same = run_rtiow("diff " + a.string() + " " + b.string());
  EXPECT_EQ(same.exit_code, 0) << same.stdout_text;
  EXPECT_NE(same.stdout_text.find("noise-aware"), std::string::npos);
  const CommandResult mutated = run_rtiow("diff " + a.string() + " " + turned.string());
  EXPECT_EQ(mutated.exit_code, 2) << mutated.stdout_text;
  const CommandResult refused = run_rtiow("diff " + a.string() + " " + small.string());
  EXPECT_EQ(refused.exit_code, 3);
  EXPECT_EQ(count_lines(refused.stderr_text), 1) << refused.stderr_text;
  EXPECT_NE(refused.stderr_text.find("differ in size"), std::string::npos);
  const CommandResult missing = run_rtiow("diff " + a.string() + " /nonexistent.exr");
  EXPECT_EQ(missing.exit_code, 4);
  EXPECT_EQ(count_lines(missing.stderr_text), 1) << missing.stderr_text;
  EXPECT_EQ(missing.stdout_text.find("FAILURE"), std::string::npos) << missing.stdout_text;
  EXPECT_EQ(run_rtiow("diff --mdoe plain " + a.string() + " " + b.string()).exit_code, 4);
  EXPECT_EQ(run_rtiow("diff " + a.string()).exit_code, 4) << "no test image";

  // Several renders: compared by their spread (Student's t); a mismatched one is named.
  const CommandResult seeds =
      run_rtiow("diff " + a.string() + " " + b.string() + " " + turned.string() + " " + a.string());
  EXPECT_NE(seeds.stdout_text.find("from 3 renders (t, 2 d.o.f.)"), std::string::npos)
      << seeds.stdout_text;
  const CommandResult mixed =
      run_rtiow("diff " + a.string() + " " + b.string() + " " + small.string());
  EXPECT_EQ(mixed.exit_code, 3);
  EXPECT_EQ(count_lines(mixed.stderr_text), 1) << mixed.stderr_text;
  EXPECT_NE(mixed.stderr_text.find("-s.exr' against the reference"), std::string::npos)
      << mixed.stderr_text;
  const CommandResult plain_of_several =
      run_rtiow("diff --mode plain " + a.string() + " " + b.string() + " " + b.string());
  EXPECT_EQ(plain_of_several.exit_code, 4);
  EXPECT_NE(plain_of_several.stderr_text.find("--mode seeds"), std::string::npos);
  EXPECT_EQ(run_rtiow("diff --mode seeds " + a.string() + " " + b.string()).exit_code, 4);
  // Thresholds and alpha are finite amounts: NaN would make every comparison false.
  for (const char* option : {"--alpha nan", "--fail nan", "--hardfail inf", "--warn -1"}) {
    const CommandResult r =
        run_rtiow(std::string("diff ") + option + " " + a.string() + " " + b.string());
    EXPECT_EQ(r.exit_code, 4) << option;
    EXPECT_EQ(count_lines(r.stderr_text), 1) << option << ": " << r.stderr_text;
  }
}

// Plain thresholds given for failure alone: the warning ones follow them (idiff's --warn
// defaults to 1e-6, which would make every image of two seeds WARN).
TEST(Cli, DiffWarningThresholdsFollowTheFailureOnesGiven) {
  const std::string render = "render -q --scene cover --width 48 --height 27 --spp 8 ";
  const fs::path a = output_path("warn-a.png"), b = output_path("warn-b.png");
  ASSERT_EQ(run_rtiow(render + "--seed 1 -o " + a.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow(render + "--seed 2 -o " + b.string()).exit_code, 0);
  const std::string both = " " + a.string() + " " + b.string();
  const CommandResult loose = run_rtiow("diff --mode plain --fail 1 --failpercent 100" + both);
  EXPECT_EQ(loose.exit_code, 0) << loose.stdout_text;
  EXPECT_NE(loose.stdout_text.find("PASS"), std::string::npos) << loose.stdout_text;
  // A warning threshold given still counts on its own.
  const CommandResult warned =
      run_rtiow("diff --mode plain --fail 1 --failpercent 100 --warn 0.001 --warnpercent 1" + both);
  EXPECT_EQ(warned.exit_code, 1) << warned.stdout_text;
  EXPECT_NE(warned.stdout_text.find("WARNING"), std::string::npos) << warned.stdout_text;
}

// A PNG whose header claims `side` x `side` pixels and holds none.
std::string png_claiming(std::uint32_t side) {
  const auto crc32 = [](const std::string& bytes) {
    std::uint32_t crc = 0xffffffffu;
    for (const unsigned char b : bytes) {
      crc ^= b;
      for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return ~crc;
  };
  const auto be32 = [](std::uint32_t v) {
    return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
  };
  const auto chunk = [&](const std::string& type, const std::string& data) {
    return be32(std::uint32_t(data.size())) + type + data + be32(crc32(type + data));
  };
  const std::string header = be32(side) + be32(side) + std::string{8, 2, 0, 0, 0};
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", header) +
         chunk("IDAT", std::string("\x78\x9c\x03\x00\x00\x00\x00\x01", 8)) + chunk("IEND", "");
}

// A header that lies about its size is refused before anything is allocated.
TEST(Cli, DiffRefusesAnImageWhoseHeaderClaimsTooManyPixels) {
  const fs::path huge = output_path("huge.png"), small = output_path("small.png");
  rtiow::test::write_file(huge, png_claiming(1000000));
  ASSERT_EQ(run_rtiow("render -q --scene cover --width 8 --height 8 --spp 1 -o " + small.string())
                .exit_code,
            0);
  const CommandResult r = run_rtiow("diff " + huge.string() + " " + small.string());
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_EQ(count_lines(r.stderr_text), 1) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("pixels"), std::string::npos) << r.stderr_text;

  // A truncated PNG: libpng's own complaint stays off stderr, OpenImageIO's joins the line.
  const fs::path truncated = output_path("truncated.png");
  rtiow::test::write_file(truncated, png_claiming(8).substr(0, 40));
  const CommandResult cut = run_rtiow("diff " + small.string() + " " + truncated.string());
  EXPECT_EQ(cut.exit_code, 4);
  EXPECT_EQ(count_lines(cut.stderr_text), 1) << cut.stderr_text;
}

TEST(Cli, ListsTheBuiltinScenes) {
  const CommandResult r = run_rtiow("render --list-scenes");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* scene : {"materials", "wide-angle", "viewpoint", "defocus", "cover"}) {
    EXPECT_NE(r.stdout_text.find(scene), std::string::npos) << scene;
  }
}

TEST(Cli, RefusesBadCamerasAndSettingsWithOneLineAndExitTwo) {
  expect_refused("--scene materials --lookfrom 0,0,-1", "lookfrom equals lookat");
  expect_refused("--scene materials --vup 0,0,-1", "vup is parallel");
  expect_refused("--vfov 0", "vfov");
  expect_refused("--vfov 180", "vfov");
  expect_refused("--width 0", "width");
  expect_refused("--spp 0", "spp");
  expect_refused("--spp -4", "spp");
  expect_refused("--scene nowhere", "unknown scene 'nowhere'");
  expect_refused("--accel magic", "unknown accelerator");
  expect_refused("--width ten", "--width");
  expect_refused("--no-such-option", "no-such-option");
}

// A slip gets the nearest real name, a value of the wrong kind the kind expected, and the
// hint names the help of the command used (issue 43: the top-level help lists no render option).
TEST(Cli, OptionErrorsSuggestWhatWasMeant) {
  expect_refused("--widht 100", "unknown option '--widht' for rtiow render; did you mean --width?");
  expect_refused("--sed 3", "did you mean --seed?");
  expect_refused("--acel naive", "did you mean --accel?");
  expect_refused("--width=100x", "--width expects a whole number, not '100x'");
  expect_refused("--spp ten", "--spp expects a whole number, not 'ten' (see rtiow render --help)");
  // A whole number beyond the option's type: the range, not "expects a whole number".
  expect_refused("--spp 99999999999",
                 "--spp: '99999999999' is beyond the largest value it takes, 2147483647");
  expect_refused("--target-error often", "--target-error: must be a finite number");
  // Too few or too many values for a vector: how many, and how to write them.
  expect_refused("--lookfrom 1,2",
                 "--lookfrom takes 3 numbers, got 2 (as --lookfrom 1,2,3, with commas or spaces "
                 "between; see rtiow render --help)");
  expect_refused("--vup 0 1 0 0", "--vup takes 3 numbers, got 4");
  // An option of one value given twice (it said "takes 1 numbers"), and a range in the help's
  // own words (it said "Value 0 not in range 0.000000 to 0.500000"), issue 70.
  expect_refused("--spp 4 --spp 8",
                 "--spp takes one value, got 2: give it once (see rtiow render --help)");
  expect_refused("--scene cover --target-error 0.1 --min-spp 1",
                 "--min-spp must be >= 2 (a variance needs two), got 1");
  expect_refused("--image-error 2",
                 "--image-error 2 is a relative error of 100% or more: give a fraction below 1");
  expect_refused("--target-error 1.5", "--target-error 1.5 is a relative error of 100% or more");
  expect_refused("--scene cover --spp 8 --min-spp 4",
                 "--min-spp 4 applies to adaptive sampling (--target-error, --image-error or "
                 "--adaptive)");
  const CommandResult alpha = run_rtiow("diff --alpha 0 a.png b.png");
  EXPECT_EQ(alpha.exit_code, 4) << alpha.stderr_text;
  EXPECT_NE(alpha.stderr_text.find("--alpha: must be from 1e-12 to 0.5, got 0 (see rtiow diff "
                                   "--help)"),
            std::string::npos)
      << alpha.stderr_text;
  const CommandResult block = run_rtiow("diff --block 0 a.png b.png");
  EXPECT_NE(block.stderr_text.find("--block: must be from 1 to 4096, got 0"), std::string::npos)
      << block.stderr_text;
  // A directory that takes no new files is what to act on, not the lock's name (issue 70).
  const CommandResult proc = run_rtiow("render -q --width 8 --spp 1 -o /proc/rtiow-x.png");
  EXPECT_EQ(proc.exit_code, 2);
  EXPECT_NE(proc.stderr_text.find("output '/proc/rtiow-x.png': cannot create files in directory "
                                  "'/proc': "),
            std::string::npos)
      << proc.stderr_text;
  // No command at all: the commands there are, not CLI11's "A subcommand is required".
  const CommandResult bare = run_rtiow("");
  EXPECT_EQ(bare.exit_code, 2);
  EXPECT_EQ(bare.stderr_text,
            "rtiow: error: no command given: rtiow COMMAND [OPTIONS], where COMMAND is one of "
            "render, scene, merge, denoise, bench, accuracy, diff (see rtiow --help)\n");
  // A value outside an option's choices: the choices in words and the one meant.
  expect_refused("--sampler sobel",
                 "--sampler: 'sobel' is not one of independent, sobol, padded-sobol; did you mean "
                 "sobol? (see rtiow render --help)");
  expect_refused("--roulette of", "did you mean off?");
  expect_refused("--fresnel schlik", "did you mean schlick?");
  expect_refused("--accel embre", "unknown accelerator 'embre'; did you mean embree?");
  // Nothing near enough: no suggestion.
  const CommandResult far = run_rtiow("render --zzzzzz 1");
  EXPECT_EQ(far.exit_code, 2);
  EXPECT_EQ(far.stderr_text.find("did you mean"), std::string::npos) << far.stderr_text;
  // The other commands and rtiow itself.
  const CommandResult diff = run_rtiow("diff --alfa 0.1 a.png b.png");
  EXPECT_NE(diff.stderr_text.find("did you mean --alpha? (see rtiow diff --help)"),
            std::string::npos)
      << diff.stderr_text;
  const CommandResult mode = run_rtiow("diff --mode nois a.png b.png");
  EXPECT_EQ(mode.exit_code, 4) << "diff's 2 is a FAILURE verdict";
  EXPECT_NE(mode.stderr_text.find("did you mean noise? (see rtiow diff --help)"), std::string::npos)
      << mode.stderr_text;
  const CommandResult version = run_rtiow("--verison");
  EXPECT_EQ(version.exit_code, 2);
  EXPECT_NE(version.stderr_text.find("did you mean --version?"), std::string::npos)
      << version.stderr_text;
  const CommandResult command = run_rtiow("rendr --spp 4");
  EXPECT_EQ(command.exit_code, 2);
  EXPECT_NE(command.stderr_text.find("unknown command 'rendr'; did you mean render?"),
            std::string::npos)
      << command.stderr_text;
}

// The natural slips between a scene's name and a scene file, and a scene written as an image.
// Every whole number reads as a user writes it, in decimal (issue 69): CLI11 read a leading
// zero as octal ("--crop 010,..." rendered the region at x 8, "--seed 09" was refused as too
// large) and 0x as hexadecimal.
TEST(Cli, WholeNumbersAreDecimalInEveryCommand) {
  const fs::path image = output_path("decimal.png");
  CommandResult r = run_rtiow(
      "render -q --scene spheres:12 --scene-seed 010 --width 040 --spp 02 "
      "--depth 05 --seed 09 --threads 01 --crop 010,0,020,05 -o " +
      image.string());
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  auto in = OIIO::ImageInput::open(image.string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  EXPECT_EQ(spec.get_string_attribute("rtiow:crop"), "10,0,20,5");
  EXPECT_EQ(spec.get_string_attribute("rtiow:frame"), "40x27");
  EXPECT_EQ(spec.get_int_attribute("rtiow:seed"), 9);
  EXPECT_EQ(spec.get_int_attribute("rtiow:scene_seed"), 10);
  EXPECT_EQ(spec.get_int_attribute("rtiow:spp"), 2);
  EXPECT_EQ(spec.get_int_attribute("rtiow:depth"), 5);
  in.reset();
  fs::remove(image);
  // Another base is refused by name, in every command.
  for (const std::string& args :
       {std::string("render --width 0x20"), std::string("render --crop 0,0,0x8,8"),
        std::string("scene spheres:10 --scene-seed 0b11"), std::string("bench --repeat 0x3"),
        std::string("accuracy --width 0o20"), std::string("diff --block 0x10 a.png b.png")}) {
    r = run_rtiow(args);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_NE(r.stderr_text.find("is not a decimal number"), std::string::npos)
        << args << ": " << r.stderr_text;
  }
  // A leading zero in the other commands' whole numbers is decimal too.
  const fs::path scene = output_path("decimal.json");
  ASSERT_EQ(run_rtiow("scene spheres:10 --scene-seed 010 -o " + scene.string()).exit_code, 0);
  ASSERT_EQ(run_rtiow("scene spheres:10 --scene-seed 10 -o " + image.string() + ".json").exit_code,
            0);
  EXPECT_EQ(slurp(scene), slurp(image.string() + ".json"));
  fs::remove(scene), fs::remove(image.string() + ".json");
}

TEST(Cli, SceneNamesAndFilesPointToEachOther) {
  expect_refused("cover",
                 "no scene file 'cover'; the built-in scene is rendered with --scene cover");
  expect_refused("--scene base.json", "a scene file is given by its path, without --scene");
  expect_refused("--scene covr", "unknown scene 'covr'; did you mean cover?");
  const fs::path png = output_path("scene.png");
  const CommandResult r = run_rtiow("scene cover -o " + png.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("a scene is JSON, not an image"), std::string::npos)
      << r.stderr_text;
  EXPECT_FALSE(fs::exists(png));
}

// A refine from 25% to 100% of its samples, at 30% after one second: 70% to go at 5% a second
// is 14 s (counting the checkpoint's 25% as this run's work said 2.3 s, issue 43).
TEST(Cli, TheTimeToGoCountsOnlyThisRunsWork) {
  EXPECT_DOUBLE_EQ(rtiow::seconds_to_go(300, 250, 1000, 1.0), 14.0);
  EXPECT_DOUBLE_EQ(rtiow::seconds_to_go(300, 0, 1000, 1.0), 7.0 / 3.0);  // a fresh render
  EXPECT_LT(rtiow::seconds_to_go(250, 250, 1000, 1.0), 0.0);             // no rate yet
  EXPECT_DOUBLE_EQ(rtiow::seconds_to_go(1000, 250, 1000, 3.0), 0.0);
}

// The live rate leaves out a denoised error target's judgements, finished and under way, as
// the summary's does (it sagged to 1.3 Mrays/s while the denoiser judged).
TEST(Cli, TheLiveRateLeavesOutTheJudgements) {
  rtiow::RenderProgress progress;
  progress.rays_traced = 4000000, progress.judging_seconds = 1.0;
  rtiow::ProgressSnapshot now = rtiow::snapshot(progress, 3.0);
  EXPECT_DOUBLE_EQ(now.judging_seconds, 1.0);
  EXPECT_DOUBLE_EQ(rtiow::live_mrays_per_second(now), 2.0);
  // A judgement under way for at least half a second counts too.
  progress.judging_since_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(
          (std::chrono::steady_clock::now() - std::chrono::milliseconds(500)).time_since_epoch())
          .count();
  now = rtiow::snapshot(progress, 3.0);
  EXPECT_GE(now.judging_seconds, 1.5);
}

// Every mode shows how far it is toward its end (issue 60): the share of its samples, budget or
// time, the time to go where one is honest, and the error targets' figures.
TEST(Cli, EveryModeShowsHowFarItIsTowardItsEnd) {
  using rtiow::ProgressSnapshot;
  rtiow::RenderSettings s;
  s.width = 10, s.height = 10;
  ProgressSnapshot now;
  now.samples_done = 2500, now.elapsed = 1.0, now.loop_seconds = 0.9;
  s.samples = rtiow::FixedSamples{100};
  rtiow::ProgressStatus p = rtiow::progress_status(s, 100, now);
  EXPECT_DOUBLE_EQ(p.fraction, 0.25);
  EXPECT_DOUBLE_EQ(p.seconds_to_go, 3.0);
  // With a time limit, whichever end is nearer.
  s.time_limit_seconds = 10.0, now.loop_seconds = 8.0;
  p = rtiow::progress_status(s, 100, now);
  EXPECT_DOUBLE_EQ(p.fraction, 0.8);
  EXPECT_DOUBLE_EQ(p.seconds_to_go, 2.0);
  // A time limit alone, resumed after 5 s: the limit counts those.
  s.samples = rtiow::UntilTimeLimit{}, now.loop_seconds = 2.5, now.seconds_before = 5.0;
  p = rtiow::progress_status(s, 100, now);
  EXPECT_DOUBLE_EQ(p.fraction, 0.75);
  EXPECT_DOUBLE_EQ(p.seconds_to_go, 2.5);
  // --adaptive's budget: unknown until the first round is judged, then in rays.
  s.time_limit_seconds = 0.0, now.seconds_before = 0.0;
  s.samples = rtiow::AdaptiveBudget{100, 16};
  now.rays_traced = 200000, now.loop_seconds = 2.0;
  p = rtiow::progress_status(s, 100, now);
  EXPECT_LT(p.fraction, 0.0);
  EXPECT_LT(p.seconds_to_go, 0.0);
  now.budget_rays = 1e6, now.spent_rays = 2e5, now.rays_at_judgement = 200000;
  now.rays_traced = 500000, now.loop_seconds = 5.0;
  p = rtiow::progress_status(s, 100, now);
  EXPECT_DOUBLE_EQ(p.fraction, 0.5);
  EXPECT_DOUBLE_EQ(p.seconds_to_go, 5.0);
  // The error targets: the error reached against the one asked, and no time to go.
  s.samples = rtiow::ImageErrorTarget{0.02, 8192, 16};
  p = rtiow::progress_status(s, 100, now);
  EXPECT_EQ(p.detail, "error ? (asked 0.02)");
  now.image_error = 0.031;
  p = rtiow::progress_status(s, 100, now);
  EXPECT_EQ(p.detail, "error 0.031 (asked 0.02)");
  EXPECT_LT(p.fraction, 0.0);
  EXPECT_LT(p.seconds_to_go, 0.0);
  s.samples = rtiow::PixelErrorTarget{0.05, 8192, 16}, now.pixels_above_target = 37;
  EXPECT_EQ(rtiow::progress_status(s, 100, now).detail, "37 of 100 pixels above error 0.05");
  s.time_limit_seconds = 10.0;  // and a time limit's share beside it
  EXPECT_DOUBLE_EQ(rtiow::progress_status(s, 100, now).fraction, 0.5);
}

// The work after a render or around a merge (the parts read, the denoiser): its share, its time so
// far and to go at the rate so far.
TEST(Cli, TheWorkAfterARenderShowsItsShareAndTimeToGo) {
  EXPECT_EQ(rtiow::work_progress_line("denoised", 25, 100, 3.0),
            " 25.0% denoised  elapsed 3.0s  ETA 9.0s");
  EXPECT_EQ(rtiow::work_progress_line("denoised", 0, 100, 0.6),
            "  0.0% denoised  elapsed 0.6s  ETA ?");
  EXPECT_EQ(rtiow::work_progress_line("of the parts read", 150, 100, 70.0),
            "100.0% of the parts read  elapsed 1m10s  ETA 0.0s");
}

// In a log, a phase past its first two seconds says how far it is, a line per tenth, as the
// render does ("progress:"); the next phase starts its own lines; nothing once a signal has asked
// for the end.
TEST(Cli, ALongDenoiseShowsItsProgressInALog) {
  const fs::path log = output_path("denoise-progress.log");
  std::fflush(stderr);
  const int saved = ::dup(STDERR_FILENO);
  const int file = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  ASSERT_GE(saved, 0);
  ASSERT_GE(file, 0);
  ::dup2(file, STDERR_FILENO);  // a file: no terminal, plain lines
  ::close(file);
  const auto read_log = [&] {
    std::fflush(stderr);
    std::ifstream in(log);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const auto wait_for = [&](const std::string& text) {
    for (int tries = 0; tries < 200 && read_log().find(text) == std::string::npos; ++tries)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    return read_log().find(text) != std::string::npos;
  };
  const auto begun_seconds_ago = [](rtiow::WorkProgress& work, std::uint64_t total, int seconds) {
    work.begin(total);
    work.start_ns =
        std::chrono::duration_cast<std::chrono::nanoseconds>(
            (std::chrono::steady_clock::now() - std::chrono::seconds(seconds)).time_since_epoch())
            .count();
  };
  rtiow::WorkProgress reading, denoising;
  std::atomic<bool> stop{false};
  bool parts = false, first = false, second = false;
  {
    const rtiow::WorkDisplay display({{&reading, "of the parts read"}, {&denoising, "denoised"}},
                                     &stop);
    begun_seconds_ago(reading, 8, 3);
    reading.done = 5;
    parts = wait_for("progress:  62.5% of the parts read  elapsed 3.");
    reading.done = 8;
    begun_seconds_ago(denoising, 1000, 3);
    denoising.done = 250;
    first = wait_for("progress:  25.0% denoised  elapsed 3.");
    denoising.done = 610;
    second = wait_for("progress:  61.0% denoised");
    stop = true, denoising.done = 900;
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  }
  const std::string shown = read_log();
  std::fflush(stderr);
  ::dup2(saved, STDERR_FILENO);
  ::close(saved);
  EXPECT_TRUE(parts) << shown;
  EXPECT_TRUE(first) << shown;
  EXPECT_TRUE(second) << shown;
  EXPECT_EQ(shown.find("90.0%"), std::string::npos) << "a line after the stop: " << shown;
  EXPECT_EQ(std::count(shown.begin(), shown.end(), '\n'), 3) << shown;
}

// What a log shows of each mode: a share and an ETA, or the error against the one asked; and a
// zero error target, which no render reaches, is refused rather than taken as "off".
TEST(Cli, AdaptiveAndTimedRendersShowProgressInALog) {
  // Each long enough for a log's line (one a second at most).
  const std::string base = "render --scene cover --width 160 --height 90 --checkpoint 0 -o ";
  for (const char* mode : {" --time-limit 2.5", " --adaptive --spp 800"}) {
    const CommandResult r = run_rtiow(base + output_path("share.png").string() + mode);
    ASSERT_EQ(r.exit_code, 0) << mode << ": " << r.stderr_text;
    EXPECT_NE(r.stderr_text.find("%  elapsed"), std::string::npos) << mode << ": " << r.stderr_text;
    EXPECT_NE(r.stderr_text.find("ETA "), std::string::npos) << mode << ": " << r.stderr_text;
  }
  const CommandResult error =
      run_rtiow(base + output_path("error.png").string() + " --image-error 0.01");
  ASSERT_EQ(error.exit_code, 0) << error.stderr_text;
  EXPECT_NE(error.stderr_text.find("progress: "), std::string::npos) << error.stderr_text;
  EXPECT_NE(error.stderr_text.find("(asked 0.01)"), std::string::npos) << error.stderr_text;
  for (const char* option : {"--image-error 0", "--target-error 0"}) {
    const CommandResult zero = run_rtiow(base + output_path("zero.png").string() + " " + option);
    EXPECT_EQ(zero.exit_code, 2) << option;
    EXPECT_NE(zero.stderr_text.find("must be a finite number > 0"), std::string::npos)
        << zero.stderr_text;
  }
}

// --preview (issue 61): the output is replaced while the render runs, each preview a whole
// image whose metadata says how far the render is; the finished file is the one a render
// without --preview writes, byte for byte, and nothing else is left.
TEST(Cli, APreviewShowsTheRenderAsItGoesAndTheFinishedFileIsTheSame) {
  const fs::path dir = empty_output_dir(test_name() + "-dir");
  const fs::path watched = dir / "watched.exr";
  BackgroundRender r({"render", "-q", "--scene", "cover", "--width", "160", "--spp", "1000000",
                      "--checkpoint", "0", "--preview", "0.1", "--passes", "depth", "-o",
                      watched.string()});
  ASSERT_TRUE(r.wait_until_rendering());
  std::string how_far;
  for (int i = 0; i < 1000 && how_far.empty(); ++i) {  // within 20 s
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    std::error_code none;
    if (!fs::exists(watched, none)) continue;
    auto in = OIIO::ImageInput::open(watched.string());
    ASSERT_TRUE(in) << "a preview is a whole image";
    how_far = in->spec().get_string_attribute("rtiow:preview");
    EXPECT_EQ(in->spec().width, 160);
    EXPECT_GE(in->spec().channelindex("Z"), 0) << "a preview holds the passes";
  }
  EXPECT_NE(how_far.find(" of 1000000 spp after "), std::string::npos) << how_far;
  r.signal(SIGTERM);
  EXPECT_EQ(r.wait(60.0), 128 + SIGTERM) << r.stderr_text();
  EXPECT_EQ(rtiow::test::names_in(dir), std::vector<std::string>{"watched.exr"});

  // A render of several passes, previewed at every pass, and the same render unwatched (with
  // the albedo, normal and depth passes, which the previews hold too).
  const std::string job =
      "render -q --scene cover --width 200 --spp 400 --reproducible --passes "
      "albedo,normal,depth -o ";
  const CommandResult w =
      run_rtiow(job + (dir / "w.exr").string() + " --preview 0.01 --checkpoint 0.01");
  ASSERT_EQ(w.exit_code, 0) << w.stderr_text;
  ASSERT_EQ(run_rtiow(job + (dir / "plain.exr").string()).exit_code, 0);
  EXPECT_TRUE(slurp(dir / "w.exr") == slurp(dir / "plain.exr")) << "the watched file differs";
  EXPECT_EQ(rtiow::test::names_in(dir),
            (std::vector<std::string>{"plain.exr", "w.exr", "watched.exr"}));
  // A share of a render is no image to watch.
  const CommandResult part = run_rtiow("render -q --width 16 --spp 4 --part 0/2 --preview 1 -o " +
                                       (dir / "p.exr").string());
  EXPECT_EQ(part.exit_code, 2);
  EXPECT_NE(part.stderr_text.find("--preview shows a whole render"), std::string::npos)
      << part.stderr_text;
}

TEST(Cli, RefusesUnwritableOutputsBeforeRendering) {
  const CommandResult bad_ext =
      run_rtiow("render -q --spp 1 --width 8 -o " + output_path("image.nosuchformat").string());
  EXPECT_EQ(bad_ext.exit_code, 2);
  EXPECT_NE(bad_ext.stderr_text.find("not an image format rtiow writes"), std::string::npos);
  const CommandResult bad_dir = run_rtiow("render -q --spp 1 --width 8 -o /nonexistent-dir/x.png");
  EXPECT_EQ(bad_dir.exit_code, 2);
  EXPECT_NE(bad_dir.stderr_text.find("does not exist"), std::string::npos);
}

}  // namespace
