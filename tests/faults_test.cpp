// Nothing lost, the executable as a user meets faults: renders killed with SIGKILL, or ended by
// INT, TERM, HUP, QUIT or XCPU, at random moments (in the middle of a pass, of a checkpoint
// write, of the final image write) and resumed end with the file an uninterrupted render
// writes, byte for byte, in every sampling mode; a finished render refines to more samples; a
// final write that fails keeps the render; memory limits at every stage end in one line and
// keep what was rendered; a checkpoint of another request is refused in one line; closed
// standard descriptors break nothing, and output lost on the way to stdout is an error. (Full
// disks, limits and unwritable targets under every format: the hostile battery,
// hostile_input_test.cpp.)

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "tests/background_render.h"
#include "tests/launch.h"
#include "tests/test_files.h"

namespace {

namespace fs = std::filesystem;
using rtiow::test::BackgroundRender;
using rtiow::test::current_test_name;
using rtiow::test::slurp;

struct CommandResult {
  int exit_code;
  std::string stderr_text;
};

using rtiow::test::launch;
using rtiow::test::Launch;
using rtiow::test::words;

CommandResult run_rtiow(const std::vector<std::string>& args) {
  const fs::path err = fs::path(RTIOW_TEST_OUTPUT_DIR) / (current_test_name() + ".run.stderr");
  Launch command;
  command.argv = args;
  command.argv.insert(command.argv.begin(), RTIOW_BINARY);
  command.stderr_path = err.string();
  return {launch(command), slurp(err)};
}

// chattr with `args` (its complaints dropped): whether it succeeded.
bool chattr(const std::vector<std::string>& args) {
  Launch command;
  command.argv = {"chattr"};
  command.argv.insert(command.argv.end(), args.begin(), args.end());
  return launch(command) == 0;
}

fs::path fresh_dir() {
  const fs::path dir = fs::path(RTIOW_TEST_OUTPUT_DIR) / (current_test_name() + ".dir");
  // A run killed while a file was immutable (ImmutableTargetKeepsTheRender) left it so.
  if (fs::exists(dir)) chattr({"-R", "-i", dir.string()});
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Makes a file immutable for as long as it lives (chattr +i), and mutable again however the
// test ends, so no build tree is left with a file that cannot be removed.
class ImmutableFile {
 public:
  explicit ImmutableFile(const fs::path& path) : path_(path) {
    applied_ = chattr({"+i", path_.string()});
  }
  ~ImmutableFile() { release(); }
  ImmutableFile(const ImmutableFile&) = delete;
  ImmutableFile& operator=(const ImmutableFile&) = delete;
  bool applied() const { return applied_; }
  void release() {
    if (applied_) chattr({"-i", path_.string()});
    applied_ = false;
  }

 private:
  fs::path path_;
  bool applied_ = false;
};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

// After a render whose final write failed: the same request with --resume writes the file an
// uninterrupted render writes.
void expect_resume_writes_the_render(const std::vector<std::string>& request, const fs::path& out,
                                     const fs::path& dir) {
  const CommandResult resumed = run_rtiow(with(request, {"-q", "--resume", "-o", out.string()}));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.stderr_text;
  const fs::path direct = dir / "direct.png";
  ASSERT_EQ(run_rtiow(with(request, {"-q", "--checkpoint", "0", "-o", direct.string()})).exit_code,
            0);
  EXPECT_TRUE(slurp(out) == slurp(direct)) << "the kept render is not the render";
}

// Whether a file whose name starts with `prefix` is in `dir` (a temporary being written).
bool has_file_starting(const fs::path& dir, const std::string& prefix) {
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(dir, error)) {
    if (entry.path().filename().string().rfind(prefix, 0) == 0) return true;
  }
  return false;
}

// Kills the render when `moment` says: after a delay, or as soon as a temporary of the
// checkpoint or of the image appears (the middle of that write). Returns whether it was
// killed at that moment (not after it had ended).
enum class Moment { Delay, CheckpointWrite, ImageWrite };

bool kill_at(BackgroundRender& r, Moment moment, double delay_seconds, const fs::path& dir,
             const std::string& output_name, int sig = SIGKILL) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  std::string checkpoint_temp = ".", image_temp = ".";  // the writers' temporaries
  checkpoint_temp.append(output_name).append(".rtiow-checkpoint.rtiow-tmp-");
  image_temp.append(output_name).append(".rtiow-tmp-");
  if (moment == Moment::Delay) {
    std::this_thread::sleep_for(std::chrono::duration<double>(delay_seconds));
  } else {
    const std::string& prefix = moment == Moment::CheckpointWrite ? checkpoint_temp : image_temp;
    while (std::chrono::steady_clock::now() < deadline && !has_file_starting(dir, prefix)) {
      int status = 0;
      if (waitpid(r.pid(), &status, WNOHANG) == r.pid()) return false;  // ended before
    }
  }
  r.signal(sig);
  // Killed, or for a signal rtiow catches, ended by it (128 + the signal), not exited before.
  return r.wait(20.0) == (sig == SIGKILL ? -2 : 128 + sig);
}

// The file each mode's request writes uninterrupted (the base request plus the mode's options),
// as `reference<m><extension>` in `dir`.
std::vector<std::string> uninterrupted_files(const fs::path& dir,
                                             const std::vector<std::string>& base,
                                             const std::vector<std::vector<std::string>>& modes,
                                             const std::string& extension) {
  std::vector<std::string> files;
  for (std::size_t m = 0; m < modes.size(); ++m) {
    const std::string path = (dir / ("reference" + std::to_string(m) + extension)).string();
    const CommandResult r =
        run_rtiow(with(with(base, modes[m]), {"--checkpoint", "0", "-o", path}));
    EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
    files.push_back(slurp(path));
  }
  return files;
}

TEST(Checkpoint, RendersKilledAtRandomMomentsResumeToTheSameFile) {
  const fs::path dir = fresh_dir();
  const std::vector<std::string> base = {"render", "--scene",        "cover", "--width",
                                         "160",    "--reproducible", "-q"};
  // Each mode's request, and its uninterrupted file.
  const std::vector<std::vector<std::string>> modes = {
      {"--spp", "96", "--stats-channels"},
      {"--spp", "64", "--sampler", "independent", "--stats-channels"},
      {"--spp", "96", "--adaptive", "--stats-channels"},
      {"--spp", "512", "--image-error", "0.04", "--stats-channels"},
      {"--spp", "256", "--target-error", "0.06", "--stats-channels"},
      {"--spp", "192", "--part", "1/2"},
  };
  const std::vector<std::string> references = uninterrupted_files(dir, base, modes, ".exr");
  ASSERT_FALSE(HasFailure());
  const unsigned seed = std::random_device{}();
  std::mt19937 random(seed);
  SCOPED_TRACE("kill moments from seed " + std::to_string(seed));
  constexpr int kTrials = 24;  // four of each mode
  int killed_in[3] = {0, 0, 0};
  for (int trial = 0; trial < kTrials; ++trial) {
    const std::size_t m = std::size_t(trial) % modes.size();
    const Moment moment = trial % 4 == 1   ? Moment::CheckpointWrite
                          : trial % 4 == 3 ? Moment::ImageWrite
                                           : Moment::Delay;
    const double delay = std::uniform_real_distribution<double>(0.05, 0.6)(random);
    const std::string name = "killed" + std::to_string(trial) + ".exr";
    const std::string out = (dir / name).string();
    const std::vector<std::string> request = with(base, modes[m]);
    BackgroundRender r(with(request, {"--checkpoint", "0.03", "-o", out}));
    killed_in[int(moment)] += kill_at(r, moment, delay, dir, name);
    // Resumed (possibly more than once: a kill before the first checkpoint leaves nothing).
    const CommandResult resumed = run_rtiow(with(request, {"--resume", "-o", out}));
    ASSERT_EQ(resumed.exit_code, 0) << "trial " << trial << ": " << resumed.stderr_text;
    // The finished render leaves its image alone: the kill's temporaries are cleaned, the
    // checkpoint removed.
    EXPECT_FALSE(has_file_starting(dir, "." + name)) << "trial " << trial << ": a temporary left";
    EXPECT_FALSE(fs::exists(out + ".rtiow-checkpoint")) << "trial " << trial;
    EXPECT_TRUE(slurp(out) == references[m])
        << "trial " << trial << " (mode " << m << ", moment " << int(moment) << ", delay " << delay
        << "): the resumed file differs from the uninterrupted one";
  }
  // The test tests what it says: kills landed mid-render, mid-checkpoint and mid-image-write.
  EXPECT_GE(killed_in[int(Moment::Delay)], 3);
  EXPECT_GE(killed_in[int(Moment::CheckpointWrite)], 2);
  EXPECT_GE(killed_in[int(Moment::ImageWrite)], 2);
  std::printf("killed during a pass %d, a checkpoint write %d, the image write %d times\n",
              killed_in[0], killed_in[1], killed_in[2]);
}

// Every signal that ends a process by default, at random moments (in a pass, in a checkpoint
// write, in the final image write), in each adaptive mode and a uniform one: the render ends
// in its own words with its checkpoint, and --resume writes the uninterrupted file.
TEST(Checkpoint, EachSignalAtRandomMomentsResumesToTheSameFile) {
  const fs::path dir = fresh_dir();
  const std::vector<std::string> base = {"render", "--scene",        "cover", "--width",
                                         "160",    "--reproducible", "-q"};
  const std::vector<std::vector<std::string>> modes = {
      {"--spp", "96"},
      {"--spp", "96", "--adaptive"},
      {"--spp", "512", "--image-error", "0.04"},
      {"--spp", "256", "--target-error", "0.06"},
  };
  const std::vector<std::string> references = uninterrupted_files(dir, base, modes, ".png");
  ASSERT_FALSE(HasFailure());
  const unsigned seed = std::random_device{}();
  std::mt19937 random(seed);
  SCOPED_TRACE("signal moments from seed " + std::to_string(seed));
  const int signals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGXCPU};
  int ended_by_signal = 0, trial = 0;
  for (const int sig : signals) {
    for (std::size_t m = 0; m < modes.size(); ++m, ++trial) {
      const Moment moment = trial % 3 == 1   ? Moment::CheckpointWrite
                            : trial % 3 == 2 ? Moment::ImageWrite
                                             : Moment::Delay;
      const double delay = std::uniform_real_distribution<double>(0.05, 0.6)(random);
      const std::string name = "signalled" + std::to_string(trial) + ".png";
      const std::string out = (dir / name).string();
      const std::vector<std::string> request = with(base, modes[m]);
      BackgroundRender r(with(request, {"--checkpoint", "0.03", "-o", out}));
      ASSERT_TRUE(r.wait_until_rendering());
      const bool signalled = kill_at(r, moment, delay, dir, name, sig);
      ended_by_signal += signalled;
      const std::string where = std::string(strsignal(sig)) + ", mode " + std::to_string(m) +
                                ", moment " + std::to_string(int(moment));
      if (signalled) {
        // Stopped: the image of the samples done, and the checkpoint to continue it; or, when
        // the signal came during the final write, the whole image and no checkpoint.
        const bool after_render =
            r.stderr_text().find("after the render ended") != std::string::npos;
        EXPECT_EQ(fs::exists(dir / (name + ".rtiow-checkpoint")), !after_render) << where;
        EXPECT_TRUE(fs::exists(out)) << where << ": no partial image";
        EXPECT_FALSE(has_file_starting(dir, "." + name)) << where << ": a temporary left";
      }
      const CommandResult resumed = run_rtiow(with(request, {"--resume", "-o", out}));
      ASSERT_EQ(resumed.exit_code, 0) << where << ": " << resumed.stderr_text;
      EXPECT_TRUE(slurp(out) == references[m]) << where << ": the resumed file differs";
    }
  }
  EXPECT_GE(ended_by_signal, 6) << "signals must land while the render runs";
  std::printf("%d of %d signals ended a running render\n", ended_by_signal, trial);
}

// `sig` twice: the second as soon as the first is taken ("stopping" said), or after `at_most`:
// not before, or the kernel may deliver the two as one; not after a fixed pause, which a loaded
// machine's short write can outlast (30 ms did in a CI run).
void signal_twice(const BackgroundRender& r, int sig, std::chrono::milliseconds at_most) {
  r.signal(sig);
  const auto taken = std::chrono::steady_clock::now() + at_most;
  while (std::chrono::steady_clock::now() < taken &&
         r.stderr_text().find("stopping") == std::string::npos) {
    std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
  r.signal(sig);
}

// Two signals during the final write (issue 69): the second waits for the image and the
// removal of the checkpoint it finishes, so what is left is the finished render and nothing that
// contradicts it. The first lands when the image's temporary appears, the second as soon as the
// first is taken; at least one trial of five must have both inside the write.
TEST(Checkpoint, TwoSignalsDuringTheFinalWriteLeaveTheFinishedImageAndNoCheckpoint) {
  const fs::path dir = fresh_dir();
  const std::vector<std::string> request = {"render",         "--scene",      "cover", "--width",
                                            "2000",           "--spp",        "1",     "-q",
                                            "--reproducible", "--checkpoint", "0.3"};
  const fs::path reference = dir / "reference.exr";
  ASSERT_EQ(run_rtiow(with(request, {"-o", reference.string()})).exit_code, 0);
  int inside = 0;
  for (int trial = 0; trial < 5; ++trial) {
    const std::string name = "twice" + std::to_string(trial) + ".exr";
    BackgroundRender r(with(request, {"-o", (dir / name).string()}));
    ASSERT_TRUE(r.wait_until_rendering());
    std::string image_temp = ".";
    image_temp.append(name).append(".rtiow-tmp-");
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline && !has_file_starting(dir, image_temp)) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    signal_twice(r, SIGINT, std::chrono::milliseconds(200));
    const int code = r.wait(60.0);
    const std::string err = r.stderr_text();
    EXPECT_EQ(code, 128 + SIGINT) << err;
    inside += err.find("finishing the write first") != std::string::npos;
    // Either state is whole: the finished image without its checkpoint, or the render kept.
    const bool finished = fs::exists(dir / name) && slurp(dir / name) == slurp(reference);
    EXPECT_NE(finished, fs::exists(dir / (name + ".rtiow-checkpoint")))
        << "trial " << trial << ": " << err;
    EXPECT_FALSE(has_file_starting(dir, "." + name)) << "a temporary or lock left: " << err;
  }
  EXPECT_GE(inside, 1) << "no second signal landed inside a final write";
}

// A second signal while the final write denoises (`--denoise`): the denoiser stops within a row and
// the image is written as rendered, so rtiow ends after the write, not after the denoiser's
// seconds (4-6.5 s at this size on 2 cores). The render takes 2 spp (0.6 s alone, 2 s beside
// another test; a time limit of 1 s left it 1 spp there, and nothing to denoise), its error is
// estimated, then it denoises; the signals land 3, 4.5 or 6 s after it began until a pair lands
// while it denoises (a pair before that ends rtiow at once, as a second signal does there).
TEST(Faults, ASecondSignalWhileDenoisingWritesTheImageAsRendered) {
  const fs::path dir = fresh_dir();
  int inside = 0;
  for (const int delay_ms : {3000, 4500, 6000}) {
    const std::string name = "denoised" + std::to_string(delay_ms) + ".exr";
    const fs::path out = dir / name;
    BackgroundRender r({"render", "--scene", "cover", "--width", "1600", "--spp", "2", "--denoise",
                        "--reproducible", "-o", out.string()});
    ASSERT_TRUE(r.wait_until_rendering());
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    signal_twice(r, SIGINT, std::chrono::milliseconds(500));
    const int code = r.wait(60.0);
    const std::string err = r.stderr_text();
    EXPECT_EQ(code, 128 + SIGINT) << err;
    EXPECT_FALSE(has_file_starting(dir, "." + name)) << "a temporary or lock left: " << err;
    if (err.find("finishing the write first, without denoising any further") == std::string::npos)
      continue;
    ++inside;
    auto in = OIIO::ImageInput::open(out.string());
    ASSERT_TRUE(in) << "the image as rendered was not written: " << err;
    EXPECT_GT(in->spec().get_int_attribute("rtiow:spp"), 1);
    EXPECT_EQ(in->spec().find_attribute("rtiow:denoise.estimated_error"), nullptr)
        << "the denoiser ran to its end: " << err;
    EXPECT_EQ(in->spec().channelindex("noisy.R"), -1);
    break;
  }
  EXPECT_EQ(inside, 1) << "no second signal landed while the final write denoised";
}

// A render stopped short never replaces an image that was there before it (issue 69): its
// samples go to the checkpoint (and --resume finishes the new image), or, without one, beside
// the old image as NAME.partial.EXT; a render that made the file itself replaces its own.
TEST(Checkpoint, AStoppedRenderLeavesTheImageThatWasThereAsItWas) {
  const fs::path dir = fresh_dir();
  const fs::path out = dir / "kept.png";
  const std::vector<std::string> finished = {"render", "--width",        "120", "--spp",     "8",
                                             "-q",     "--reproducible", "-o",  out.string()};
  ASSERT_EQ(run_rtiow(finished).exit_code, 0);
  const std::string before = slurp(out);
  const std::vector<std::string> longer = {"render", "--width",        "120", "--spp",     "200000",
                                           "-q",     "--reproducible", "-o",  out.string()};
  for (const bool with_checkpoint : {true, false}) {
    SCOPED_TRACE(with_checkpoint ? "with a checkpoint" : "--checkpoint 0");
    BackgroundRender r(with(longer, {"--checkpoint", with_checkpoint ? "60" : "0"}));
    ASSERT_TRUE(r.wait_until_rendering());
    std::this_thread::sleep_for(std::chrono::milliseconds(400));
    r.signal(SIGINT);
    ASSERT_EQ(r.wait(60.0), 128 + SIGINT) << r.stderr_text();
    const std::string err = r.stderr_text();
    EXPECT_EQ(slurp(out), before) << "a finished image replaced by less: " << err;
    EXPECT_NE(err.find("which this render did not finish, is left as it was"), std::string::npos)
        << err;
    const fs::path partial = dir / "kept.partial.png";
    EXPECT_EQ(fs::exists(partial), !with_checkpoint) << err;
    EXPECT_EQ(fs::exists(dir / "kept.png.rtiow-checkpoint"), with_checkpoint) << err;
    fs::remove(partial);
    fs::remove(dir / "kept.png.rtiow-checkpoint");
  }
  // Its own preview replaced the file already: the stopped image goes there, as before.
  BackgroundRender previewed(with(longer, {"--checkpoint", "0", "--preview", "0.1"}));
  ASSERT_TRUE(previewed.wait_until_rendering());
  std::this_thread::sleep_for(std::chrono::milliseconds(600));
  previewed.signal(SIGINT);
  ASSERT_EQ(previewed.wait(60.0), 128 + SIGINT) << previewed.stderr_text();
  EXPECT_NE(slurp(out), before);
  EXPECT_FALSE(fs::exists(dir / "kept.partial.png"));
}

TEST(Checkpoint, FinishedRenderRefinesToTheFileOfTheLargerCount) {
  const fs::path dir = fresh_dir();
  const std::vector<std::string> base = {"render", "--scene",        "cover", "--width",
                                         "120",    "--reproducible", "-q"};
  const std::string direct = (dir / "direct.png").string(),
                    refined = (dir / "refined.png").string();
  ASSERT_EQ(run_rtiow(with(base, {"--spp", "40", "-o", direct})).exit_code, 0);
  ASSERT_EQ(run_rtiow(with(base, {"--spp", "10", "--keep-state", "-o", refined})).exit_code, 0);
  const CommandResult r =
      run_rtiow(with(base, {"--spp", "40", "--resume", "--keep-state", "-o", refined}));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_TRUE(slurp(direct) == slurp(refined)) << "10 then 40 spp is not the 40-spp file";
  EXPECT_FALSE(fs::exists(direct + ".rtiow-checkpoint")) << "kept without --keep-state";
  // Back to fewer samples than the checkpoint holds: refused, naming the count.
  const CommandResult fewer = run_rtiow(with(base, {"--spp", "20", "--resume", "-o", refined}));
  EXPECT_EQ(fewer.exit_code, 2);
  EXPECT_NE(fewer.stderr_text.find("already has 40 spp"), std::string::npos) << fewer.stderr_text;
}

TEST(Checkpoint, ResumeRefusesTheCheckpointOfAnotherRequest) {
  const fs::path dir = fresh_dir();
  const std::string out = (dir / "c.png").string();
  ASSERT_EQ(run_rtiow({"render", "-q", "--width", "60", "--spp", "4", "--keep-state", "-o", out})
                .exit_code,
            0);
  const std::string before = slurp(out);
  const CommandResult r = run_rtiow(
      {"render", "-q", "--width", "60", "--spp", "4", "--seed", "9", "--resume", "-o", out});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("seed: the checkpoint's '1', this render's '9'"), std::string::npos)
      << r.stderr_text;
  EXPECT_EQ(std::count(r.stderr_text.begin(), r.stderr_text.end(), '\n'), 1) << r.stderr_text;
  EXPECT_TRUE(slurp(out) == before) << "the refused render touched the image";
  // With no checkpoint at all, --resume renders from the start and says so.
  const std::string other = (dir / "other.png").string();
  const CommandResult fresh =
      run_rtiow({"render", "--width", "60", "--spp", "4", "--resume", "-o", other});
  EXPECT_EQ(fresh.exit_code, 0) << fresh.stderr_text;
  EXPECT_NE(fresh.stderr_text.find("rendering from the start"), std::string::npos);
}

TEST(Checkpoint, FailedFinalWriteKeepsTheRenderToWriteLater) {
  const fs::path dir = fresh_dir();
  const std::vector<std::string> request = {"render", "--scene", "cover", "--width",
                                            "160",    "--spp",   "600",   "--reproducible"};
  const fs::path out = dir / "blocked.png";
  BackgroundRender r(with(request, {"-o", out.string()}));
  ASSERT_TRUE(r.wait_until_rendering());
  // The target becomes a directory with something in it: no rename can replace it.
  fs::create_directories(out / "in-the-way");
  const int code = r.wait(120.0);
  const std::string err = r.stderr_text();
  EXPECT_EQ(code, 1) << err;
  EXPECT_NE(err.find("the render is kept in"), std::string::npos) << err;
  EXPECT_NE(err.find("--resume"), std::string::npos) << err;
  EXPECT_EQ(err.find(".tmp-"), std::string::npos) << "names an internal temporary: " << err;
  fs::remove_all(out);
  expect_resume_writes_the_render(request, out, dir);
}

// The output's directory removed during the render: neither the image nor the checkpoint can
// go there, so the checkpoint goes to $TMPDIR, and the message says how to get the image.
TEST(Checkpoint, DirectoryRemovedMidRenderKeepsTheRenderInTheTemporaryDirectory) {
  const fs::path dir = fresh_dir();
  const fs::path gone = dir / "gone", tmp = dir / "tmp";
  fs::create_directories(gone);
  fs::create_directories(tmp);
  const std::vector<std::string> request = {"render", "--scene", "cover", "--width",
                                            "160",    "--spp",   "400",   "--reproducible"};
  ::setenv("TMPDIR", tmp.c_str(), 1);  // inherited by the render
  BackgroundRender r(with(request, {"-o", (gone / "x.png").string()}));
  ::unsetenv("TMPDIR");
  ASSERT_TRUE(r.wait_until_rendering());
  fs::remove_all(gone);
  EXPECT_EQ(r.wait(120.0), 1) << r.stderr_text();
  const std::string err = r.stderr_text();
  EXPECT_NE(err.find("the render is kept in '" + tmp.string() + "/rtiow-"), std::string::npos)
      << err;
  EXPECT_NE(err.find("move it to"), std::string::npos) << err;
  std::vector<fs::path> kept;
  for (const auto& entry : fs::directory_iterator(tmp)) kept.push_back(entry.path());
  ASSERT_EQ(kept.size(), 1u) << "one checkpoint in TMPDIR, no temporaries";
  fs::create_directories(gone);
  fs::rename(kept[0], gone / "x.png.rtiow-checkpoint");
  expect_resume_writes_the_render(request, gone / "x.png", dir);
}

// Two renders to one output: the second is refused before any work (both would report
// success while one replaced the other), and the lock goes with the first.
TEST(Faults, SecondRenderToTheSameOutputIsRefused) {
  const fs::path dir = fresh_dir();
  const fs::path out = dir / "same.png";
  BackgroundRender first(
      {"render", "--scene", "cover", "--width", "160", "--spp", "1000000", "-o", out.string()});
  ASSERT_TRUE(first.wait_until_rendering());
  const CommandResult second =
      run_rtiow({"render", "--width", "40", "--spp", "2", "-o", out.string()});
  EXPECT_EQ(second.exit_code, 2);
  EXPECT_NE(second.stderr_text.find("another rtiow (pid " + std::to_string(first.pid()) + ")"),
            std::string::npos)
      << second.stderr_text;
  first.signal(SIGINT);
  EXPECT_EQ(first.wait(20.0), 128 + SIGINT) << first.stderr_text();
  EXPECT_FALSE(fs::exists(dir / ".same.png.rtiow-lock")) << "the lock outlived its render";
  // The stopped render's checkpoint stays (to resume); --restart discards it.
  EXPECT_EQ(
      run_rtiow({"render", "-q", "--width", "40", "--spp", "2", "--restart", "-o", out.string()})
          .exit_code,
      0)
      << "the output is free again";
}

// The output made immutable during the render (chattr +i, which even root cannot write
// through): the image cannot replace it, the render is kept beside it, and --resume writes it
// once the flag is gone. Skipped where the file system has no immutable flag.
TEST(Faults, ImmutableTargetKeepsTheRender) {
  const fs::path dir = fresh_dir();
  const fs::path out = dir / "locked.png";
  rtiow::test::write_file(out, "the user's old image");
  const std::vector<std::string> request = {"render", "--scene", "cover", "--width",
                                            "160",    "--spp",   "400",   "--reproducible"};
  BackgroundRender r(with(request, {"-o", out.string()}));
  ASSERT_TRUE(r.wait_until_rendering());
  ImmutableFile immutable(out);
  if (!immutable.applied()) {
    r.signal(SIGKILL);
    r.wait(20.0);
    GTEST_SKIP() << "chattr +i is not available here";
  }
  const int code = r.wait(120.0);
  immutable.release();
  const std::string err = r.stderr_text();
  EXPECT_EQ(code, 1) << err;
  EXPECT_NE(err.find("cannot write '" + out.string() + "': Operation not permitted"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("the render is kept in '" + out.string() + ".rtiow-checkpoint'"),
            std::string::npos)
      << err;
  EXPECT_EQ(slurp(out), "the user's old image");
  expect_resume_writes_the_render(request, out, dir);
}

// Started with descriptors 0-2 closed (a launcher that closes them), a render writes the
// image it writes with them open.
TEST(Faults, ClosedStandardDescriptorsBreakNothing) {
  const fs::path dir = fresh_dir();
  const std::string args = " render --width 80 --spp 4 --reproducible -o ";
  const fs::path open = dir / "open.png", closed = dir / "closed.png";
  Launch opened;
  opened.argv = words(std::string(RTIOW_BINARY) + args + open.string());
  ASSERT_EQ(launch(opened), 0);
  Launch closing = opened;
  closing.argv = words(std::string(RTIOW_BINARY) + args + closed.string());
  closing.stdin_path = closing.stdout_path = closing.stderr_path = "";  // closed
  EXPECT_EQ(launch(closing), 0);
  EXPECT_TRUE(fs::exists(closed)) << "no image written with stdin, stdout and stderr closed";
  EXPECT_TRUE(slurp(open) == slurp(closed)) << "the image differs with the descriptors closed";
}

// A command's output that does not reach standard output is an error, whatever the reason.
TEST(Faults, LostStandardOutputIsAnError) {
  const fs::path dir = fresh_dir();
  const std::string err = (dir / "err.txt").string();
  const std::string rtiow = RTIOW_BINARY;
  const std::string bench = rtiow +
                            " bench --width 16 --height 9 --spp 1 --scaling-width 16 "
                            "--scaling-height 9 --scaling-spp 1 --max-spheres 10 --repeat 1 "
                            "--out " +
                            (dir / "bench").string();
  const std::string image = (dir / "i.png").string();
  Launch first;
  first.argv = words(rtiow + " render -q --width 40 --spp 2 -o " + image);
  ASSERT_EQ(launch(first), 0);
  const std::string full = "/dev/full", closed;  // closed: no path
  for (const auto& [line, out] : {std::pair{bench, full}, std::pair{bench, closed},
                                  std::pair{rtiow + " diff " + image + " " + image, full},
                                  std::pair{rtiow + " render --list-scenes", closed},
                                  std::pair{rtiow + " scene cover", full}}) {
    Launch command;
    command.argv = words(line);
    command.stdout_path = out, command.stderr_path = err;
    const std::string shown = line + (out.empty() ? " >&-" : " >" + out);
    // diff's 1 and 2 are verdicts: one nobody could read is its "could not compare".
    EXPECT_EQ(launch(command), line.find(" diff ") != std::string::npos ? 4 : 1) << shown;
    const std::string text = slurp(err);
    EXPECT_NE(text.find("rtiow: error: cannot write to standard output"), std::string::npos)
        << shown << ": " << text;
  }
  // A closed pipe: the reader leaves after 10 bytes of a scene file of many kilobytes.
  Launch piped;
  piped.argv = words(rtiow + " scene cover");
  piped.stdout_reader_bytes = 10;
  piped.stderr_path = err;
  EXPECT_EQ(launch(piped), 1);
  EXPECT_NE(slurp(err).find("cannot write to standard output"), std::string::npos) << slurp(err);
}

}  // namespace

namespace {

// Memory limits at every stage: an address-space limit from too little to start (the image
// library, Embree's device, the BVH, the film) to enough to finish. Under each, the render
// either writes the render or ends with one line in rtiow's words and leaves no temporary;
// a render that got as far as rendering keeps its work, and --resume without the limit
// writes the file of an unlimited render.
TEST(Faults, MemoryLimitsAtEveryStageEndInOneLineAndKeepWhatWasRendered) {
  const fs::path dir = fresh_dir();
  const std::vector<std::string> request = {"render", "--scene", "cover", "--width",
                                            "200",    "--spp",   "8",     "--reproducible"};
  const fs::path direct = dir / "direct.png";
  ASSERT_EQ(run_rtiow(with(request, {"-q", "--checkpoint", "0", "-o", direct.string()})).exit_code,
            0);
  const std::string expected = slurp(direct);
  int kept = 0, refused = 0, finished = 0;
  // Below 80 MB the dynamic loader itself cannot map rtiow's libraries: nothing of rtiow's runs.
  for (int megabytes = 80; megabytes <= 1200; megabytes += 40) {
    const fs::path out = dir / ("limit" + std::to_string(megabytes) + ".png");
    const fs::path err = dir / "stderr.txt";
    Launch line;
    line.argv = {"prlimit", "--as=" + std::to_string(megabytes * 1024 * 1024), RTIOW_BINARY};
    line.argv.insert(line.argv.end(), request.begin(), request.end());
    line.argv.insert(line.argv.end(), {"-q", "-o", out.string()});
    line.stderr_path = err.string();
    const int code = launch(line);
    const std::string text = slurp(err);
    const std::string where = std::to_string(megabytes) + " MB: " + text;
    for (const auto& entry : fs::directory_iterator(dir)) {
      EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos)
          << where << " left a temporary";
    }
    if (code == 0) {
      ++finished;
      EXPECT_TRUE(slurp(out) == expected) << where;
      continue;
    }
    EXPECT_EQ(code, 1) << where;
    EXPECT_EQ(text.rfind("rtiow: error: ", 0), 0u) << where;
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << where;
    EXPECT_FALSE(fs::exists(out)) << where << " left a half-written image";
    if (text.find("the render is kept in") == std::string::npos) {
      ++refused;
      continue;
    }
    ++kept;
    const CommandResult resumed = run_rtiow(with(request, {"-q", "--resume", "-o", out.string()}));
    ASSERT_EQ(resumed.exit_code, 0) << where << resumed.stderr_text;
    EXPECT_TRUE(slurp(out) == expected) << where << ": the kept render is not the render";
  }
  std::printf("limits: %d refused before rendering, %d kept the render, %d finished\n", refused,
              kept, finished);
  EXPECT_GT(refused, 0) << "no limit was low enough to stop the start";
  EXPECT_GT(finished, 0) << "no limit was high enough to finish";
}

}  // namespace
