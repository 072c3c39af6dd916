// The files rtiow writes and reads, against someone who can write the output's directory
// (issue 41): a link or a FIFO at each of rtiow's names, a file made first, a crafted
// checkpoint. Nothing rtiow creates goes through a link or into a file it did not make;
// nothing it reads can block it; every refusal is one line and exit 2.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/render/checkpoint_file.h"
#include "core/render/render.h"
#include "core/render/render_request.h"
#include "core/render/render_state.h"
#include "core/scene/builtin_scenes.h"
#include "tests/background_render.h"
#include "tests/launch.h"
#include "tests/test_files.h"

namespace {

namespace fs = std::filesystem;
using rtiow::test::BackgroundRender;
using rtiow::test::current_test_name;
using rtiow::test::names_in;
using rtiow::test::slurp;
using rtiow::test::write_file;

constexpr const char* kPrecious = "PRECIOUS: a file of the user's\n";

struct CommandResult {
  int exit_code;
  std::string stderr_text;
  double seconds;
};

// Runs rtiow with a time limit (a FIFO that hangs it fails the test rather than the suite).
CommandResult run_rtiow(const std::vector<std::string>& args, double timeout_seconds = 60) {
  const fs::path err = fs::path(RTIOW_TEST_OUTPUT_DIR) / (current_test_name() + ".run.stderr");
  rtiow::test::Launch command;
  command.argv = args;
  command.argv.insert(command.argv.begin(), RTIOW_BINARY);
  command.stderr_path = err.string();
  command.timeout_seconds = timeout_seconds;
  const auto start = std::chrono::steady_clock::now();
  const int code = rtiow::test::launch(command);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return {code, slurp(err), seconds};
}

fs::path fresh_dir() {
  const fs::path dir = fs::path(RTIOW_TEST_OUTPUT_DIR) / "security" / current_test_name();
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::vector<std::string> small_render(const fs::path& out) {
  return {"render", "-q", "--width", "32", "--height", "18", "--spp", "4", "-o", out.string()};
}

bool is_one_line(const std::string& text) {
  return std::count(text.begin(), text.end(), '\n') == 1;
}

// ---- Writing: a link at the target's name is replaced, never followed.

TEST(FileSafety, AtomicWriteReplacesALinkAtTheTargetAndLeavesItsFileAlone) {
  const fs::path dir = fresh_dir();
  write_file(dir / "precious.txt", kPrecious);
  fs::create_symlink("precious.txt", dir / "out.txt");
  rtiow::write_text_atomically((dir / "out.txt").string(), "new content");
  EXPECT_EQ(slurp(dir / "precious.txt"), kPrecious);
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir / "out.txt")));
  EXPECT_EQ(slurp(dir / "out.txt"), "new content");
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"out.txt", "precious.txt"}));
}

TEST(FileSafety, AtomicWriteThatFailsLeavesNoTemporaryAndTheTargetAsItWas) {
  const fs::path dir = fresh_dir();
  write_file(dir / "out.txt", "old");
  EXPECT_THROW(rtiow::write_atomically((dir / "out.txt").string(),
                                       [](int, std::string& reason) {
                                         reason = "the encoder gave up";
                                         return false;
                                       }),
               std::runtime_error);
  EXPECT_THROW(rtiow::write_atomically(
                   (dir / "out.txt").string(),
                   [](int, std::string&) -> bool { throw std::runtime_error("thrown mid-write"); }),
               std::runtime_error);
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"out.txt"}));
  EXPECT_EQ(slurp(dir / "out.txt"), "old");
}

// Temporaries are rtiow's own pattern with a random part: two writes never share one, and the
// cleaner takes only that pattern, only plain files, only this user's.
TEST(FileSafety, StaleTemporariesAreRemovedOnlyWhenTheyAreRtiowsOwn) {
  const fs::path dir = fresh_dir();
  write_file(dir / ".o.png.rtiow-tmp-Ab3dE6gH", "left by a kill -9");
  write_file(dir / ".o.png.rtiow-checkpoint.rtiow-tmp-12345678", "another");
  write_file(dir / "precious.txt", kPrecious);
  fs::create_symlink("precious.txt", dir / ".o.png.rtiow-tmp-LinkLink");
  write_file(dir / ".o.png.rtiow-tmp-short", "not the pattern");
  write_file(dir / ".o.png.rtiow-tmp-Ab3dE6gHx", "not the pattern");
  write_file(dir / ".other.png.rtiow-tmp-Ab3dE6gH", "another output's");
  write_file(dir / ".o.png.rtiow-tmp-Other000", "another user's");
  ASSERT_EQ(::chown((dir / ".o.png.rtiow-tmp-Other000").c_str(), 65534, 65534), 0);
  const int dir_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  ASSERT_GE(dir_fd, 0);
  EXPECT_EQ(rtiow::remove_stale_temporaries(dir_fd, "o.png"), 1);
  EXPECT_EQ(rtiow::remove_stale_temporaries(dir_fd, "o.png.rtiow-checkpoint"), 1);
  ::close(dir_fd);
  EXPECT_EQ(names_in(dir),
            (std::vector<std::string>{".o.png.rtiow-tmp-Ab3dE6gHx", ".o.png.rtiow-tmp-LinkLink",
                                      ".o.png.rtiow-tmp-Other000", ".o.png.rtiow-tmp-short",
                                      ".other.png.rtiow-tmp-Ab3dE6gH", "precious.txt"}));
  EXPECT_EQ(slurp(dir / "precious.txt"), kPrecious);
  EXPECT_TRUE(rtiow::is_temporary_of("o.png", ".o.png.rtiow-tmp-Ab3dE6gH"));
  EXPECT_FALSE(rtiow::is_temporary_of("o.png", ".o.png.rtiow-tmp-Ab3dE6g/"));
}

// Every file a command writes, with a link at its name to a file of the user's: the link is
// replaced by the output, the file it pointed to is untouched.
TEST(FileSafety, EveryCommandsOutputReplacesALinkAtItsName) {
  const fs::path dir = fresh_dir();
  write_file(dir / "precious.txt", kPrecious);
  const fs::path part = dir / "part.exr";
  ASSERT_EQ(run_rtiow({"render", "-q", "--width", "24", "--spp", "4", "--part", "0/1", "-o",
                       part.string()})
                .exit_code,
            0);
  const std::vector<std::pair<std::string, std::vector<std::string>>> commands = {
      {"r.png", {"render", "-q", "--width", "24", "--spp", "2", "-o"}},
      {"r.exr", {"render", "-q", "--width", "24", "--spp", "2", "--stats-channels", "-o"}},
      {"r.jpg", {"render", "-q", "--width", "24", "--spp", "2", "-o"}},
      {"p.exr", {"render", "-q", "--width", "24", "--spp", "4", "--part", "1/2", "-o"}},
      {"s.json", {"scene", "cover", "-o"}},
      {"m.png", {"merge", part.string(), "-o"}},
      {"d.png", {"diff", part.string(), part.string(), "--out-diff"}},
  };
  for (const auto& [name, args] : commands) {
    SCOPED_TRACE(name);
    fs::create_symlink("precious.txt", dir / name);
    std::vector<std::string> full = args;
    full.push_back((dir / name).string());
    const CommandResult r = run_rtiow(full);
    EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
    EXPECT_EQ(slurp(dir / "precious.txt"), kPrecious);
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir / name)));
  }
  for (const std::string& name : names_in(dir)) {
    EXPECT_EQ(name.find("rtiow-"), std::string::npos) << "left behind: " << name;
  }
}

// ---- The lock: never through a link, never someone else's file, never fails open.

TEST(FileSafety, ALockNameThatIsNotRtiowsOwnFileIsRefusedAndLeftAlone) {
  const fs::path dir = fresh_dir();
  const fs::path out = dir / "o.png", lock = dir / ".o.png.rtiow-lock";
  write_file(dir / "precious.txt", kPrecious);
  const auto expect_refused = [&](const std::string& what, const std::string& why) {
    SCOPED_TRACE(what);
    const CommandResult r = run_rtiow(small_render(out), 20);
    EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
    EXPECT_NE(r.stderr_text.find("cannot take its lock"), std::string::npos) << r.stderr_text;
    EXPECT_NE(r.stderr_text.find(why), std::string::npos) << r.stderr_text;
    EXPECT_TRUE(is_one_line(r.stderr_text)) << r.stderr_text;
    EXPECT_FALSE(fs::exists(out)) << "rendered without its lock";
    EXPECT_EQ(slurp(dir / "precious.txt"), kPrecious);
    EXPECT_TRUE(fs::exists(fs::symlink_status(lock))) << "removed what it did not make";
    fs::remove(lock);
  };
  fs::create_symlink("precious.txt", lock);
  expect_refused("a link", "symbolic link");
  fs::create_symlink("nowhere", lock);
  expect_refused("a dangling link", "symbolic link");
  fs::create_directory(lock);
  expect_refused("a directory", "directory");
  ASSERT_EQ(::mkfifo(lock.c_str(), 0600), 0);
  expect_refused("a FIFO", "not a regular file");
  fs::create_hard_link(dir / "precious.txt", lock);
  expect_refused("a hard link", "hard links");
  write_file(lock, "4242\n");
  ASSERT_EQ(::chown(lock.c_str(), 65534, 65534), 0);
  expect_refused("another user's file", "another user");
  // A lock a killed render left (this user's plain file, no holder) is taken and removed.
  write_file(lock, "99999\n");
  const CommandResult r = run_rtiow(small_render(out));
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"o.png", "precious.txt"}));
}

// ---- Reading: a FIFO, a device or a directory where a file is read is refused at once.

TEST(FileSafety, NoInputCanBlockOrBeSomethingOtherThanAFile) {
  const fs::path dir = fresh_dir();
  const fs::path fifo = dir / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const fs::path out = dir / "o.png";
  ASSERT_EQ(::mkfifo((dir / "o.png.rtiow-checkpoint").c_str(), 0600), 0);
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"scene file", {"render", fifo.string(), "-o", (dir / "x.png").string()}},
      {"checkpoint", {"render", "--width", "16", "--spp", "2", "--resume", "-o", out.string()}},
      {"checkpoint", {"render", "--width", "16", "--spp", "2", "-o", out.string()}},
      {"part file", {"merge", fifo.string(), "-o", (dir / "m.png").string()}},
      {"image", {"diff", fifo.string(), fifo.string()}},
      {"scene file", {"render", "/dev/zero", "-o", (dir / "x.png").string()}},
      {"scene file", {"render", dir.string(), "-o", (dir / "x.png").string()}},
  };
  for (const auto& [what, args] : cases) {
    SCOPED_TRACE(what + " " + args[1]);
    const CommandResult r = run_rtiow(args, 20);
    EXPECT_EQ(r.exit_code, args[0] == "diff" ? 4 : 2) << r.stderr_text;  // diff's 2: FAILURE
    EXPECT_LT(r.seconds, 10.0) << "blocked";
    EXPECT_NE(r.stderr_text.find(what), std::string::npos) << r.stderr_text;
    EXPECT_TRUE(is_one_line(r.stderr_text)) << r.stderr_text;
  }
  // A checkpoint is never read through a link (rtiow writes none).
  fs::remove(dir / "o.png.rtiow-checkpoint");
  write_file(dir / "precious.txt", kPrecious);
  fs::create_symlink("precious.txt", dir / "o.png.rtiow-checkpoint");
  const CommandResult linked =
      run_rtiow({"render", "-q", "--width", "16", "--spp", "2", "--resume", "-o", out.string()});
  EXPECT_EQ(linked.exit_code, 2);
  EXPECT_NE(linked.stderr_text.find("symbolic link"), std::string::npos) << linked.stderr_text;
  // --restart discards the link (not the file it names) and renders.
  const CommandResult restarted =
      run_rtiow({"render", "-q", "--width", "16", "--spp", "2", "--restart", "-o", out.string()});
  EXPECT_EQ(restarted.exit_code, 0) << restarted.stderr_text;
  EXPECT_EQ(slurp(dir / "precious.txt"), kPrecious);
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir / "o.png.rtiow-checkpoint")));
}

// ---- Checkpoints: never discarded silently; a finished render leaves only its image.

TEST(FileSafety, ACheckpointIsNeverDiscardedSilently) {
  const fs::path dir = fresh_dir();
  const fs::path out = dir / "c.png", checkpoint = dir / "c.png.rtiow-checkpoint";
  const std::vector<std::string> request = {"render",       "--width", "120", "--spp",     "100000",
                                            "--checkpoint", "0.05",    "-o",  out.string()};
  BackgroundRender r(request);
  ASSERT_TRUE(r.wait_until_rendering());
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  r.signal(SIGTERM);
  ASSERT_EQ(r.wait(20.0), 128 + SIGTERM) << r.stderr_text();
  ASSERT_TRUE(fs::exists(checkpoint));
  const std::string kept = slurp(checkpoint);
  // The same command again: refused, naming both ways forward, the checkpoint untouched.
  const CommandResult again = run_rtiow(request);
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_NE(again.stderr_text.find("--resume"), std::string::npos) << again.stderr_text;
  EXPECT_NE(again.stderr_text.find("--restart"), std::string::npos) << again.stderr_text;
  EXPECT_NE(again.stderr_text.find("spp done"), std::string::npos) << again.stderr_text;
  EXPECT_TRUE(is_one_line(again.stderr_text)) << again.stderr_text;
  // Another request to the same output: refused too, naming what differs.
  std::vector<std::string> other = request;
  other.insert(other.end() - 2, {"--seed", "5"});
  const CommandResult different = run_rtiow(other);
  EXPECT_EQ(different.exit_code, 2);
  EXPECT_NE(different.stderr_text.find("seed"), std::string::npos) << different.stderr_text;
  EXPECT_TRUE(slurp(checkpoint) == kept) << "a refused render touched the checkpoint";
  // --restart discards it: a short render, and then only the image is left.
  const CommandResult restarted =
      run_rtiow({"render", "-q", "--width", "40", "--spp", "2", "--restart", "-o", out.string()});
  EXPECT_EQ(restarted.exit_code, 0) << restarted.stderr_text;
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"c.png"}));
}

TEST(FileSafety, AFinishedRenderLeavesOnlyWhatWasAskedFor) {
  const fs::path dir = fresh_dir();
  ASSERT_EQ(run_rtiow(small_render(dir / "plain.png")).exit_code, 0);
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"plain.png"}));
  std::vector<std::string> keep = small_render(dir / "kept.png");
  keep.push_back("--keep-state");
  ASSERT_EQ(run_rtiow(keep).exit_code, 0);
  EXPECT_EQ(names_in(dir),
            (std::vector<std::string>{"kept.png", "kept.png.rtiow-checkpoint", "plain.png"}));
  // The kept state is compact: well under version 2's 156 bytes a pixel.
  const auto bytes = fs::file_size(dir / "kept.png.rtiow-checkpoint");
  EXPECT_LT(bytes, std::uintmax_t(32 * 18 * 60 + 1024)) << bytes << " bytes for 576 pixels";
}

// The output's directory swapped for a link to another mid-render (issue 69): every write and
// the finished render's removal of its checkpoint go through the directory the claim holds
// open, so the image and the removal land where the render began, and a file of the same name
// in the other directory is left alone.
TEST(FileSafety, ADirectorySwappedMidRenderChangesNothingElsewhere) {
  const fs::path dir = fresh_dir();
  const fs::path began = dir / "began", moved = dir / "moved", other = dir / "other";
  fs::create_directories(began);
  fs::create_directories(other);
  write_file(other / "o.png.rtiow-checkpoint", kPrecious);
  BackgroundRender r({"render", "-q", "--width", "160", "--spp", "400", "--checkpoint", "0.05",
                      "-o", (began / "o.png").string()});
  ASSERT_TRUE(r.wait_until_rendering());
  // Its checkpoint is there (a periodic save), then the directory goes and a link takes it.
  for (int i = 0; i < 2000 && !fs::exists(began / "o.png.rtiow-checkpoint"); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(fs::exists(began / "o.png.rtiow-checkpoint")) << "no periodic save seen";
  fs::rename(began, moved);
  fs::create_directory_symlink("other", began);
  ASSERT_EQ(r.wait(120.0), 0) << r.stderr_text();
  EXPECT_EQ(slurp(other / "o.png.rtiow-checkpoint"), kPrecious) << "removed another's file";
  EXPECT_FALSE(fs::exists(other / "o.png")) << "written through the link";
  EXPECT_TRUE(fs::exists(moved / "o.png")) << "the image not where the render began";
  EXPECT_FALSE(fs::exists(moved / "o.png.rtiow-checkpoint")) << "its own checkpoint left";
}

// A cleaner of temporary files removes both lock files while a render runs (issue 69): a
// second render of the same output is still refused before any work, and the first finishes
// as if nothing had happened.
TEST(FileSafety, ALockHoldsWhenACleanerRemovesItsFile) {
  const fs::path dir = fresh_dir();
  const fs::path out = dir / "o.png";
  BackgroundRender first({"render", "-q", "--width", "160", "--spp", "200", "-o", out.string()});
  ASSERT_TRUE(first.wait_until_rendering());
  for (const char* lock : {".o.png.rtiow-lock", ".o.png.rtiow-checkpoint.rtiow-lock"}) {
    ASSERT_TRUE(fs::remove(dir / lock)) << lock;
  }
  rtiow::test::Launch second;
  second.argv = {RTIOW_BINARY, "render", "-q", "--width", "16", "--spp", "1", "-o", out.string()};
  const fs::path err = dir / "second.stderr";
  second.stderr_path = err.string();
  EXPECT_EQ(rtiow::test::launch(second), 2);
  EXPECT_NE(slurp(err).find("another rtiow is writing it (its lock file was removed)"),
            std::string::npos)
      << slurp(err);
  ASSERT_EQ(first.wait(120.0), 0) << first.stderr_text();
  // The image is the first render's: its PNG header says 160 wide (big-endian, bytes 16-19).
  const std::string png = slurp(out);
  ASSERT_GE(png.size(), 24u);
  const auto byte = [&](std::size_t i) {
    return std::uint32_t(static_cast<unsigned char>(png[i]));
  };
  EXPECT_EQ(byte(16) << 24 | byte(17) << 16 | byte(18) << 8 | byte(19), 160u);
  // Once the first has ended, the output is free again.
  EXPECT_EQ(rtiow::test::launch(second), 0) << slurp(err);
}

// ---- Output from libraries is rtiow's or absent; threads above the cores are used.

TEST(FileSafety, MoreThreadsThanCoresPrintNothingWhenQuiet) {
  const fs::path dir = fresh_dir();
  std::vector<std::string> args = small_render(dir / "t.png");
  args.insert(args.end() - 2, {"--threads", "37"});
  const CommandResult r = run_rtiow(args);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.stderr_text, "");
}

// ---- A crafted checkpoint: each field within what the request allows, or refused.

class CraftedCheckpoint : public ::testing::Test {
 protected:
  fs::path dir_ = fresh_dir();
  rtiow::Scene scene_ = rtiow::make_builtin_scene("cover", 1);
  rtiow::RenderSettings settings_;

  // An adaptive render's state at its first round, as the command line would keep it.
  rtiow::RenderState adaptive_state(const rtiow::RenderRequest& request) {
    const rtiow::ResolvedRender job = rtiow::resolve(scene_, request);
    settings_ = job.settings;
    rtiow::RenderState saved{0};
    rtiow::Checkpointing keep;
    keep.save = [&](const rtiow::RenderState& state, rtiow::SaveReason) { saved = state; };
    rtiow::render(job.scene, job.settings, nullptr, &keep);
    return saved;
  }

  std::string refusal(const rtiow::RenderState& state) {
    const std::string path = (dir_ / "c.rtiow-checkpoint").string();
    const rtiow::RenderIdentity id = rtiow::render_identity(scene_, settings_);
    rtiow::write_checkpoint(path, id, state);
    try {
      rtiow::read_checkpoint(path, id, settings_);
    } catch (const rtiow::InvalidInput& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(CraftedCheckpoint, EveryFieldOutsideTheRequestsLimitsIsRefused) {
  rtiow::RenderRequest request;
  request.width = 12, request.height = 8, request.spp = 64, request.adaptive = true;
  request.min_samples = 4;
  const rtiow::RenderState good = adaptive_state(request);
  ASSERT_EQ(refusal(good), "") << "the honest state is read";
  const auto refused = [&](const char* what, auto change, const std::string& expected) {
    SCOPED_TRACE(what);
    rtiow::RenderState state = good;
    change(state);
    const std::string why = refusal(state);
    EXPECT_NE(why.find(expected), std::string::npos) << "got: " << why;
  };
  using State = rtiow::RenderState;
  refused(
      "a target far above the cap",
      [](State& s) { s.targets.assign(s.pixels.samples.size(), 4), s.targets[3] = 0xFFFFFFFFu; },
      "adaptive target outside 0 to 16777216");
  // (the header's most_samples, or the pixel's own count: either names the cap)
  refused(
      "a count above the cap", [](State& s) { s.pixels.samples[5] = 0xFFFFFFFFu; },
      "0 to 16777216");
  refused(
      "a time that is not a number", [](State& s) { s.render_seconds = std::nan(""); },
      "render_seconds");
  refused(
      "a negative time", [](State& s) { s.render_seconds = -1e300; }, "render_seconds");
  refused(
      "more time judging than rendering",
      [](State& s) { s.judging_seconds = s.render_seconds + 1; }, "judging_seconds");
  refused(
      "a judging time that is not a number", [](State& s) { s.judging_seconds = std::nan(""); },
      "judging_seconds");
  refused(
      "an infinite time", [](State& s) { s.render_seconds = INFINITY; }, "render_seconds");
  refused(
      "more rays than the samples trace",
      [](State& s) {
        s.pixels.rays[2] += 1000000;
        s.rays_traced += 1000000;
      },
      "more rays than its samples can trace");
  refused(
      "rays that do not add up", [](State& s) { s.rays_traced += 1; }, "rays_traced");
  refused(
      "a sum no samples reach",
      [](State& s) { s.pixels.sums.color[1].set_channel(0, rtiow::int128(1) << 100); },
      "sums no samples can add up to");
  refused(
      "a negative sum", [](State& s) { s.pixels.sums.spreads[1].odd.set_channel(2, -1); },
      "sums no samples can add up to");
  refused(
      "a replicate's sum above its pixel's",
      [](State& s) {
        s.pixels.sums.spreads[1].odd.set_channel(0, s.pixels.sums.color[1].channel(0) + 1);
      },
      "odd.R is more than sum.R");
  refused(
      "squares too small for their sum",
      [](State& s) { s.pixels.sums.spreads[1].squares.set_channel(1, 0); }, "squares.G is less");
  refused(
      "an image error that is not a number",
      [](State& s) { s.estimated_image_error = std::nan(""); }, "estimated_image_error");
  refused(
      "more pixels above the target than pixels",
      [](State& s) { s.pixels_above_target = 1u << 30; }, "pixels_above_target");
}

// A resumed state with a pixel given the most work the cap allows is stopped by a signal within
// about a second (a pixel advances in steps, each asking whether to stop).
TEST_F(CraftedCheckpoint, AResumedRenderHonoursASignalSoon) {
  rtiow::RenderRequest request;
  request.width = 12, request.height = 8, request.spp = 64, request.adaptive = true;
  request.min_samples = 4;
  rtiow::RenderState state = adaptive_state(request);
  ASSERT_FALSE(state.targets.empty());
  state.targets[0] = rtiow::limits::kMostAdaptiveSamples;  // minutes of work on one pixel
  const fs::path out = dir_ / "r.png";
  rtiow::write_checkpoint(out.string() + ".rtiow-checkpoint",
                          rtiow::render_identity(scene_, settings_), state);
  BackgroundRender r({"render", "--width", "12", "--height", "8", "--spp", "64", "--adaptive",
                      "--min-spp", "4", "--resume", "-o", out.string()});
  ASSERT_TRUE(r.wait_until_rendering());
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const auto signalled = std::chrono::steady_clock::now();
  r.signal(SIGTERM);
  EXPECT_EQ(r.wait(30.0), 128 + SIGTERM) << r.stderr_text();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
  EXPECT_LT(seconds, 5.0) << "the signal waited for the pixel";
  EXPECT_NE(r.stderr_text().find("interrupted: wrote"), std::string::npos) << r.stderr_text();
}

}  // namespace
