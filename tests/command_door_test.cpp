// Every command goes through the same door as render (issue 59): the files it writes are
// claimed (a lock, a held directory, exclusive temporaries renamed into place), no shell ever
// runs, state that is not the user's own is never continued, and every signal that would end
// the process ends it in rtiow's words with nothing left behind. Each test runs the commands
// as a user would and as someone who can write the output's directory would.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/background_render.h"
#include "tests/test_files.h"

namespace {

namespace fs = std::filesystem;
using rtiow::test::BackgroundRender;
using rtiow::test::current_test_name;
using rtiow::test::names_in;
using rtiow::test::slurp;
using rtiow::test::write_file;

constexpr const char* kPrecious = "PRECIOUS: a file of the user's\n";

struct CommandRun {
  int exit_code;
  std::string stderr_text;
};

// The user rtiow runs as: the test's, or another (nobody, through util-linux's setpriv: the
// tests run as root, whom no directory's sticky bit or file mode stops).
enum class RunAs { Tester, Nobody };

// rtiow with an argument vector (no shell here either: the names hold quotes), in `cwd`.
CommandRun run_in(const fs::path& cwd, const std::vector<std::string>& args, double seconds = 120,
                  RunAs as = RunAs::Tester) {
  const fs::path err = fs::path(RTIOW_TEST_OUTPUT_DIR) / (current_test_name() + ".door.stderr");
  std::vector<std::string> full = {"/usr/bin/timeout", "-s", "KILL", std::to_string(int(seconds)),
                                   RTIOW_BINARY};
  if (as == RunAs::Nobody) {
    full.insert(full.begin(),
                {"/usr/bin/setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"});
  }
  full.insert(full.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : full) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(cwd.c_str()) != 0) _exit(126);
    const int in = ::open("/dev/null", O_RDONLY);
    const int out = ::open("/dev/null", O_WRONLY);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in < 0 || out < 0 || e < 0) _exit(126);
    ::dup2(in, 0), ::dup2(out, 1), ::dup2(e, 2);
    ::execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(err)};
}

fs::path fresh_dir() {
  const fs::path dir = fs::path(RTIOW_TEST_OUTPUT_DIR) / "door" / current_test_name();
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

bool one_line(const std::string& text) {
  return !text.empty() && text.back() == '\n' && std::count(text.begin(), text.end(), '\n') == 1;
}

// Whether anything of rtiow's own (a lock, a temporary) is left in `dir`.
std::string leftovers(const fs::path& dir) {
  std::string found;
  for (const std::string& name : names_in(dir)) {
    if (name.find(".rtiow-lock") != std::string::npos ||
        name.find(".rtiow-tmp-") != std::string::npos) {
      found += name + " ";
    }
  }
  return found;
}

// Waits (up to 20 s) until `pid` has used `seconds` of CPU: a render past its set-up, even on
// a loaded machine.
void wait_for_cpu_seconds(pid_t pid, double seconds) {
  const long ticks = ::sysconf(_SC_CLK_TCK);
  for (int i = 0; i < 2000; ++i) {
    const std::string stat = slurp("/proc/" + std::to_string(pid) + "/stat");
    const std::size_t close = stat.rfind(')');
    if (close == std::string::npos) return;
    std::istringstream fields(stat.substr(close + 2));
    std::string field;
    long long user = 0, system = 0;
    for (int k = 3; k <= 15 && fields >> field; ++k) {
      if (k == 14) user = std::stoll(field);
      if (k == 15) system = std::stoll(field);
    }
    if (double(user + system) / double(ticks) >= seconds) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

void make_part(const fs::path& dir, const std::string& name) {
  ASSERT_EQ(run_in(dir, {"render", "-q", "--width", "24", "--height", "16", "--spp", "2", "--part",
                         "0/1", "-o", name})
                .exit_code,
            0);
}

// What each command writes, and the arguments that make it write `name` (in the cwd).
struct Writer {
  std::string label;
  std::string name;  // the file it writes
  std::vector<std::string> args;
};

std::vector<Writer> writers() {
  return {
      {"render",
       "r.png",
       {"render", "-q", "--width", "24", "--height", "16", "--spp", "2", "-o", "r.png"}},
      {"part",
       "p.exr",
       {"render", "-q", "--width", "24", "--height", "16", "--spp", "2", "--part", "0/1", "-o",
        "p.exr"}},
      {"merge", "m.png", {"merge", "part.exr", "-o", "m.png"}},
      {"diff", "d.png", {"diff", "part.exr", "part.exr", "--out-diff", "d.png"}},
      {"scene", "s.json", {"scene", "cover", "-o", "s.json"}},
  };
}

// The exit code of a refused command: diff keeps 2 for its FAILURE verdict (idiff's codes).
int refusal_code(const Writer& w) {
  return w.label == "diff" ? 4 : 2;
}

// ---- No shell: any name works as --out, and a helper's output is a private temporary.

TEST(CommandDoor, NoShellRunsWhateverTheOutputIsCalled) {
  const fs::path dir = fresh_dir();
  for (const std::string out :
       {"b'; touch PWNED; echo '", "John's \"bench\" $(touch PWNED2)", "-dash and\nnewline"}) {
    SCOPED_TRACE(out);
    const CommandRun r = run_in(dir, {"bench", "--quick", "--out=" + out});
    EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
    EXPECT_TRUE(fs::is_regular_file(dir / out / "bench.json")) << r.stderr_text;
    EXPECT_TRUE(fs::is_regular_file(dir / out / "bench.png"))
        << "the plot, drawn through the helper's stdout: " << r.stderr_text;
    EXPECT_EQ(slurp(dir / out / "bench.png").substr(0, 8), "\x89PNG\r\n\x1a\n");
    EXPECT_EQ(leftovers(dir / out), "");
  }
  EXPECT_FALSE(fs::exists(dir / "PWNED"));
  EXPECT_FALSE(fs::exists(dir / "PWNED2"));
  EXPECT_FALSE(fs::exists("PWNED"));
}

TEST(CommandDoor, PlotsAndFiguresReplaceALinkAtTheirNameAndLeaveItsFileAlone) {
  const fs::path dir = fresh_dir();
  write_file(dir / "precious.txt", kPrecious);
  fs::create_directories(dir / "b");
  fs::create_symlink("../precious.txt", dir / "b" / "bench.png");
  fs::create_symlink("../precious.txt", dir / "b" / "bench.json");
  fs::create_symlink("../precious.txt", dir / "b" / "bench.csv");
  const CommandRun r = run_in(dir, {"bench", "--quick", "--out", "b"});
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_EQ(slurp(dir / "precious.txt"), kPrecious);
  for (const char* name : {"bench.png", "bench.json", "bench.csv"}) {
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir / "b" / name))) << name;
  }
  EXPECT_EQ(names_in(dir / "b"),
            (std::vector<std::string>{"bench.csv", "bench.json", "bench.png"}));
}

// A measurement refused at its outputs writes nothing.
TEST(CommandDoor, AMeasurementWhoseOutputsCannotBeClaimedWritesNothing) {
  const fs::path dir = fresh_dir();
  fs::create_directories(dir / "taken");
  ASSERT_EQ(::mkfifo((dir / "taken" / ".bench.png.rtiow-lock").c_str(), 0600), 0);
  const CommandRun r = run_in(dir, {"bench", "--quick", "--out", "taken"});
  EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
  EXPECT_TRUE(one_line(r.stderr_text)) << r.stderr_text;
  EXPECT_EQ(names_in(dir / "taken"), (std::vector<std::string>{".bench.png.rtiow-lock"}));
  EXPECT_FALSE(fs::exists(dir / "taken" / "bench.json")) << "refused before its work";
  // Ended by a signal before its files are written: the directories it made go again.
  BackgroundRender bench({"bench", "--out", (dir / "new" / "deeper").string()});
  const fs::path lock = dir / "new" / "deeper" / ".bench.png.rtiow-lock";
  for (int i = 0; i < 2000 && !(fs::exists(lock) && fs::file_size(lock) > 0); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  bench.signal(SIGTERM);
  EXPECT_EQ(bench.wait(30.0), 128 + SIGTERM) << bench.stderr_text();
  EXPECT_NE(bench.stderr_text().find("rtiow: ended by signal 15 (SIGTERM)"), std::string::npos)
      << bench.stderr_text();
  EXPECT_FALSE(fs::exists(dir / "new")) << "left the directories it made";
}

// ---- One output, one writer: two commands of any kinds aimed at one file, one refuses.

TEST(CommandDoor, TwoCommandsAimedAtOneOutputOneRefusesInOneLine) {
  const fs::path dir = fresh_dir();
  make_part(dir, "part.exr");
  for (const std::string target : {"o.png", "o.exr"}) {
    SCOPED_TRACE(target);
    BackgroundRender holder({"render", "-q", "--width", "400", "--spp", "100000", "--checkpoint",
                             "0", "-o", (dir / target).string()});
    ASSERT_TRUE(holder.wait_until_rendering());
    wait_for_cpu_seconds(holder.pid(), 0.5);  // rendering, past the scene's set-up
    const std::vector<std::vector<std::string>> others = {
        {"render", "-q", "--width", "24", "--spp", "2", "-o", target},
        {"merge", "part.exr", "-o", target},
        {"diff", "part.exr", "part.exr", "--out-diff", target},
    };
    for (const auto& args : others) {
      SCOPED_TRACE(args[0]);
      const CommandRun r = run_in(dir, args);
      EXPECT_EQ(r.exit_code, args[0] == "diff" ? 4 : 2) << r.stderr_text;  // diff's 2: FAILURE
      EXPECT_NE(r.stderr_text.find("another rtiow (pid " + std::to_string(holder.pid())),
                std::string::npos)
          << r.stderr_text;
      EXPECT_TRUE(one_line(r.stderr_text)) << r.stderr_text;
    }
    holder.signal(SIGTERM);
    EXPECT_EQ(holder.wait(30.0), 128 + SIGTERM) << holder.stderr_text();
    EXPECT_TRUE(fs::is_regular_file(dir / target)) << "the holder's work: " << holder.stderr_text();
    EXPECT_EQ(leftovers(dir), "");
  }
  // A measurement's files too, claimed before its work: a scene aimed at bench.json waits for
  // no one and is refused.
  BackgroundRender bench({"bench", "--quick", "--out", (dir / "b").string()});
  const fs::path lock = dir / "b" / ".bench.json.rtiow-lock";
  for (int i = 0; i < 2000 && !(fs::exists(lock) && fs::file_size(lock) > 0); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const CommandRun scene = run_in(dir, {"scene", "cover", "-o", "b/bench.json"});
  EXPECT_EQ(scene.exit_code, 2) << scene.stderr_text;
  EXPECT_NE(scene.stderr_text.find("another rtiow"), std::string::npos) << scene.stderr_text;
  EXPECT_EQ(bench.wait(120.0), 0) << bench.stderr_text();
  // One command naming one file twice: refused, not a lost write.
  const CommandRun twice =
      run_in(dir, {"diff", "part.exr", "part.exr", "--out-diff", "x.exr", "--out-z", "./x.exr"});
  EXPECT_EQ(twice.exit_code, 4) << twice.stderr_text;
  EXPECT_NE(twice.stderr_text.find("another output of this command"), std::string::npos)
      << twice.stderr_text;
}

// ---- Every name a command uses, per command: what rtiow never makes is refused and left.

TEST(CommandDoor, EveryCommandsLockNameRefusesWhatRtiowNeverMakes) {
  const fs::path dir = fresh_dir();
  make_part(dir, "part.exr");
  write_file(dir / "precious.txt", kPrecious);
  const std::vector<std::pair<std::string, std::function<void(const fs::path&)>>> planted = {
      {"symbolic link", [](const fs::path& at) { fs::create_symlink("precious.txt", at); }},
      {"symbolic link", [](const fs::path& at) { fs::create_symlink("nowhere", at); }},
      {"directory", [](const fs::path& at) { fs::create_directory(at); }},
      {"not a regular file", [](const fs::path& at) { ASSERT_EQ(::mkfifo(at.c_str(), 0600), 0); }},
      {"hard links",
       [&dir](const fs::path& at) { fs::create_hard_link(dir / "precious.txt", at); }},
      {"another user",
       [](const fs::path& at) {
         write_file(at, "4242\n");
         ASSERT_EQ(::chown(at.c_str(), 65534, 65534), 0);
       }},
  };
  for (const Writer& w : writers()) {
    for (const auto& [why, plant] : planted) {
      SCOPED_TRACE(w.label + ": " + why);
      std::string lock_name(1, '.');  // not "." + ...: GCC 12 warns falsely (-Wrestrict)
      lock_name.append(w.name).append(".rtiow-lock");
      const fs::path lock = dir / lock_name;
      plant(lock);
      const CommandRun r = run_in(dir, w.args, 30);
      EXPECT_EQ(r.exit_code, refusal_code(w)) << r.stderr_text;
      EXPECT_NE(r.stderr_text.find("cannot take its lock"), std::string::npos) << r.stderr_text;
      EXPECT_NE(r.stderr_text.find(why), std::string::npos) << r.stderr_text;
      EXPECT_TRUE(one_line(r.stderr_text)) << r.stderr_text;
      EXPECT_FALSE(fs::exists(dir / w.name)) << "written without its lock";
      EXPECT_TRUE(fs::exists(fs::symlink_status(lock))) << "removed what it did not make";
      EXPECT_EQ(slurp(dir / "precious.txt"), kPrecious);
      fs::remove(lock);
    }
  }
}

// An output rtiow could not replace at the end is refused before the work (issue 69): another
// user's file in a sticky directory (rename over it fails there, as /tmp's users find), and a
// file that is read-only to the user. Run as nobody, since root passes both.
TEST(CommandDoor, EveryCommandRefusesBeforeTheWorkAnOutputItCouldNotReplace) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root, to run rtiow as another user";
  const fs::path dir = fresh_dir();
  make_part(dir, "part.exr");
  ASSERT_EQ(::chmod(dir.c_str(), 01777), 0);  // world-writable and sticky, like /tmp
  ASSERT_EQ(::chmod((dir / "part.exr").c_str(), 0644), 0);
  std::vector<Writer> cases = writers();
  cases.push_back({"render's summary",
                   "r.json",
                   {"render", "-q", "--width", "24", "--height", "16", "--spp", "2", "-o",
                    "mine.png", "--summary-json", "r.json"}});
  for (const Writer& w : cases) {
    SCOPED_TRACE(w.label);
    // The tester's file (root's): another user's, to nobody.
    write_file(dir / w.name, kPrecious);
    CommandRun r = run_in(dir, w.args, 30, RunAs::Nobody);
    EXPECT_EQ(r.exit_code, refusal_code(w)) << r.stderr_text;
    EXPECT_NE(r.stderr_text.find("another user's file in a sticky directory"), std::string::npos)
        << r.stderr_text;
    EXPECT_TRUE(one_line(r.stderr_text)) << r.stderr_text;
    EXPECT_EQ(slurp(dir / w.name), kPrecious);
    EXPECT_EQ(leftovers(dir), "");
    EXPECT_FALSE(fs::exists(dir / "mine.png")) << "rendered before it was refused";
    fs::remove(dir / w.name);
    // Nobody's own file, read-only: refused too, and kept.
    write_file(dir / w.name, kPrecious);
    ASSERT_EQ(::chown((dir / w.name).c_str(), 65534, 65534), 0);
    ASSERT_EQ(::chmod((dir / w.name).c_str(), 0444), 0);
    r = run_in(dir, w.args, 30, RunAs::Nobody);
    EXPECT_EQ(r.exit_code, refusal_code(w)) << r.stderr_text;
    EXPECT_NE(r.stderr_text.find("is read-only to you"), std::string::npos) << r.stderr_text;
    EXPECT_EQ(slurp(dir / w.name), kPrecious);
    EXPECT_FALSE(fs::exists(dir / "mine.png"));
    fs::remove(dir / w.name);
    // Its own writable file: replaced, as always.
    write_file(dir / w.name, kPrecious);
    ASSERT_EQ(::chown((dir / w.name).c_str(), 65534, 65534), 0);
    r = run_in(dir, w.args, 60, RunAs::Nobody);
    EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
    EXPECT_NE(slurp(dir / w.name), kPrecious);
    EXPECT_EQ(leftovers(dir), "");
    fs::remove(dir / w.name);
    fs::remove(dir / "mine.png");
  }
}

// A lock, a temporary or a checkpoint of rtiow's is not a name any output may take: the next
// render of that image would replace or remove it (issue 69). Refused before any work, with
// what was there left alone.
TEST(CommandDoor, EveryCommandRefusesRtiowsOwnNamesAsOutputs) {
  const fs::path dir = fresh_dir();
  make_part(dir, "part.exr");
  const std::vector<std::string> own = {".o.png.rtiow-lock", "o.png.rtiow-checkpoint",
                                        ".o.png.rtiow-tmp-AbCdEfGh", "x.rtiow-tmp-12345678.png"};
  for (const std::string& name : own) {
    write_file(dir / name, kPrecious);
    const std::vector<std::pair<std::string, std::vector<std::string>>> commands = {
        {"render", {"render", "-q", "--width", "24", "--spp", "2", "-o", name}},
        {"render --summary-json",
         {"render", "-q", "--width", "24", "--spp", "2", "-o", "r.png", "--summary-json", name}},
        {"scene", {"scene", "cover", "-o", name}},
        {"merge", {"merge", "part.exr", "-o", name}},
        {"diff", {"diff", "part.exr", "part.exr", "--summary-json", name}},
        {"bench", {"bench", "--quick", "--summary-json", name}},
    };
    for (const auto& [label, args] : commands) {
      SCOPED_TRACE(label + " " + name);
      const CommandRun r = run_in(dir, args, 30);
      EXPECT_EQ(r.exit_code, label == "diff" ? 4 : 2) << r.stderr_text;
      EXPECT_NE(r.stderr_text.find("is a name rtiow gives its own files"), std::string::npos)
          << r.stderr_text;
      EXPECT_TRUE(one_line(r.stderr_text)) << r.stderr_text;
      EXPECT_EQ(slurp(dir / name), kPrecious);
      EXPECT_FALSE(fs::exists(dir / "r.png")) << "rendered before it refused";
    }
    fs::remove(dir / name);
  }
}

TEST(CommandDoor, EveryCommandsOutputNameIsReplacedNeverFollowedOrOpened) {
  const fs::path dir = fresh_dir();
  make_part(dir, "part.exr");
  write_file(dir / "precious.txt", kPrecious);
  for (const Writer& w : writers()) {
    SCOPED_TRACE(w.label);
    // A dangling link and a hard link to the user's file: replaced, the file untouched.
    fs::create_symlink("nowhere/at/all", dir / w.name);
    CommandRun r = run_in(dir, w.args);
    EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir / w.name)));
    fs::remove(dir / w.name);
    fs::create_hard_link(dir / "precious.txt", dir / w.name);
    r = run_in(dir, w.args);
    EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
    EXPECT_EQ(slurp(dir / "precious.txt"), kPrecious) << "written through a hard link";
    // A FIFO or a directory at the name: refused before any work, never opened.
    fs::remove(dir / w.name);
    ASSERT_EQ(::mkfifo((dir / w.name).c_str(), 0600), 0);
    r = run_in(dir, w.args, 20);
    EXPECT_EQ(r.exit_code, refusal_code(w)) << r.stderr_text;
    EXPECT_TRUE(one_line(r.stderr_text)) << r.stderr_text;
    fs::remove(dir / w.name);
    fs::create_directory(dir / w.name);
    r = run_in(dir, w.args, 20);
    EXPECT_EQ(r.exit_code, refusal_code(w)) << r.stderr_text;
    EXPECT_NE(r.stderr_text.find("directory"), std::string::npos) << r.stderr_text;
    fs::remove(dir / w.name);
    EXPECT_EQ(leftovers(dir), "");
  }
}

// What a kill -9 of any command left (a temporary of rtiow's pattern) is removed by the next
// command that writes that output, which holds its lock.
TEST(CommandDoor, EveryCommandSweepsTheTemporariesAKilledOneLeft) {
  const fs::path dir = fresh_dir();
  make_part(dir, "part.exr");
  for (const Writer& w : writers()) {
    SCOPED_TRACE(w.label);
    std::string left(1, '.');  // not "." + ...: GCC 12 warns falsely (-Wrestrict)
    left.append(w.name).append(".rtiow-tmp-Ab3dE6gH");
    write_file(dir / left, "half of a file a kill -9 left");
    const CommandRun r = run_in(dir, w.args);
    EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
    EXPECT_FALSE(fs::exists(dir / left)) << "left behind";
    EXPECT_TRUE(fs::is_regular_file(dir / w.name));
  }
  EXPECT_EQ(leftovers(dir), "");
}

// ---- State that is not the user's own is never continued.

TEST(CommandDoor, ACheckpointThatIsNotTheUsersOwnIsNeverResumed) {
  const fs::path dir = fresh_dir();
  const std::vector<std::string> first = {"render", "-q", "--width",      "24", "--height", "16",
                                          "--spp",  "4",  "--keep-state", "-o", "k.png"};
  ASSERT_EQ(run_in(dir, first).exit_code, 0);
  const fs::path checkpoint = dir / "k.png.rtiow-checkpoint";
  ASSERT_TRUE(fs::exists(checkpoint));
  const std::string state = slurp(checkpoint), image = slurp(dir / "k.png");
  const std::vector<std::string> more = {"render", "-q", "--width",  "24", "--height", "16",
                                         "--spp",  "8",  "--resume", "-o", "k.png"};
  ASSERT_EQ(::chown(checkpoint.c_str(), 65534, 65534), 0);
  CommandRun r = run_in(dir, more);
  EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("belongs to another user"), std::string::npos) << r.stderr_text;
  EXPECT_TRUE(one_line(r.stderr_text)) << r.stderr_text;
  ASSERT_EQ(::chown(checkpoint.c_str(), ::geteuid(), ::getegid()), 0);
  fs::create_hard_link(checkpoint, dir / "elsewhere");
  r = run_in(dir, more);
  EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("hard links"), std::string::npos) << r.stderr_text;
  EXPECT_EQ(slurp(checkpoint), state);
  EXPECT_EQ(slurp(dir / "k.png"), image);
  // Its own again: continued.
  fs::remove(dir / "elsewhere");
  r = run_in(dir, more);
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
}

// ---- Every signal that would end rtiow ends it in its words, with the work kept.

const std::vector<int>& terminating_signals() {
  static const std::vector<int> signals = [] {
    std::vector<int> s = {SIGHUP,    SIGINT,  SIGQUIT, SIGTERM, SIGUSR1, SIGUSR2,  SIGALRM,
                          SIGVTALRM, SIGPROF, SIGXCPU, SIGIO,   SIGPWR,  SIGSTKFLT};
    s.push_back(SIGRTMIN);
    s.push_back(SIGRTMAX);
    return s;
  }();
  return signals;
}

TEST(CommandDoor, EveryTerminatingSignalStopsARenderInItsWordsAndKeepsTheWork) {
  const fs::path dir = fresh_dir();
  for (const int sig : terminating_signals()) {
    SCOPED_TRACE(std::to_string(sig));
    const fs::path out = dir / (std::to_string(sig) + ".png");
    BackgroundRender r({"render", "-q", "--width", "300", "--spp", "100000", "-o", out.string()});
    ASSERT_TRUE(r.wait_until_rendering());
    wait_for_cpu_seconds(r.pid(), 0.3);
    r.signal(sig);
    EXPECT_EQ(r.wait(30.0), 128 + sig) << r.stderr_text();
    const std::string err = r.stderr_text();
    EXPECT_NE(err.find("rtiow: interrupted"), std::string::npos) << err;
    EXPECT_TRUE(fs::is_regular_file(out)) << "the samples done were written";
    EXPECT_TRUE(fs::is_regular_file(dir / (out.filename().string() + ".rtiow-checkpoint")))
        << "and the render kept to continue";
    EXPECT_EQ(leftovers(dir), "");
  }
}

// A fault of rtiow's own (here sent from outside, as a crash would raise it) ends it at once,
// said as an internal error, with its lock and temporaries removed and its last checkpoint kept.
TEST(CommandDoor, AFaultSignalEndsARenderAsAnInternalErrorWithNothingLeft) {
  const fs::path dir = fresh_dir();
  for (const int sig : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGTRAP, SIGSYS}) {
    SCOPED_TRACE(std::to_string(sig));
    const fs::path out = dir / (std::to_string(sig) + ".png");
    BackgroundRender r({"render", "-q", "--width", "300", "--spp", "100000", "--checkpoint", "0.05",
                        "-o", out.string()});
    ASSERT_TRUE(r.wait_until_rendering());
    wait_for_cpu_seconds(r.pid(), 0.3);
    r.signal(sig);
    EXPECT_EQ(r.wait(30.0), 128 + sig) << r.stderr_text();
    EXPECT_NE(r.stderr_text().find("rtiow: internal error: ended by signal " + std::to_string(sig)),
              std::string::npos)
        << r.stderr_text();
    EXPECT_TRUE(fs::is_regular_file(dir / (out.filename().string() + ".rtiow-checkpoint")))
        << "the last checkpoint is kept";
    EXPECT_EQ(leftovers(dir), "");
  }
}

// Outside a render (reading parts, building a scene, writing), a signal ends the command at
// once: in its words, on the stderr it started with, with nothing left behind.
// rtiow `args` in `dir` with its standard output to `out`, in a process group of its own (as a
// shell's foreground job is).
struct GroupRun {
  pid_t pid = -1;
  fs::path err;
};
GroupRun start_in_group(const fs::path& dir, const std::vector<std::string>& args,
                        const std::string& out) {
  GroupRun run;
  run.err = fs::path(RTIOW_TEST_OUTPUT_DIR) / (current_test_name() + ".group.stderr");
  std::vector<std::string> full = {RTIOW_BINARY};
  full.insert(full.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : full) argv.push_back(a.data());
  argv.push_back(nullptr);
  run.pid = ::fork();
  if (run.pid == 0) {
    ::setpgid(0, 0);
    for (const int sig : {SIGINT, SIGTERM}) std::signal(sig, SIG_DFL);
    if (::chdir(dir.c_str()) != 0) _exit(126);
    const int o = ::open(out.c_str(), O_WRONLY);
    const int e = ::open(run.err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (o < 0 || e < 0) _exit(126);
    ::dup2(o, 1), ::dup2(e, 2);
    ::execv(argv[0], argv.data());
    _exit(127);
  }
  ::setpgid(run.pid, run.pid);
  return run;
}

int wait_for(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Whether `parent` has a child process now.
bool has_child(pid_t parent) {
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string stat = slurp(entry.path() / "stat");
    const std::size_t close = stat.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream fields(stat.substr(close + 2));
    std::string state;
    long ppid = 0;
    if (fields >> state >> ppid && ppid == parent) return true;
  }
  return false;
}

// Nothing lost quietly (issue 69): a verdict that cannot be printed is an error in one line,
// not diff's FAILURE with nothing said; a Ctrl-C, which reaches bench and the point it runs in
// a process of its own, is said once.
TEST(CommandDoor, NothingALostVerdictOrASecondSignalLineHides) {
  const fs::path dir = fresh_dir();
  make_part(dir, "a.exr");
  ASSERT_EQ(run_in(dir, {"render", "-q", "--width", "24", "--height", "16", "--spp", "2", "--seed",
                         "2", "--part", "0/1", "-o", "b.exr"})
                .exit_code,
            0);
  for (const std::string& other : {std::string("a.exr"), std::string("b.exr")}) {
    SCOPED_TRACE(other);
    const GroupRun diff = start_in_group(dir, {"diff", "a.exr", other}, "/dev/full");
    EXPECT_EQ(wait_for(diff.pid), 4) << "a verdict nobody could read";
    const std::string err = slurp(diff.err);
    EXPECT_NE(err.find("cannot write to standard output"), std::string::npos) << err;
    EXPECT_TRUE(one_line(err)) << err;
  }

  const GroupRun bench = start_in_group(dir, {"bench", "--quick", "--out", "b"}, "/dev/null");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!has_child(bench.pid) && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::killpg(bench.pid, SIGINT);  // as a terminal's Ctrl-C: the whole foreground group
  EXPECT_EQ(wait_for(bench.pid), 128 + SIGINT);
  const std::string err = slurp(bench.err);
  EXPECT_EQ(err.substr(err.find("rtiow: ")),
            "rtiow: ended by signal 2 (SIGINT); nothing more was written\n")
      << err;
  EXPECT_FALSE(fs::exists(dir / "b")) << "the directory it made for its figures is left";
}

TEST(CommandDoor, EveryTerminatingSignalEndsOtherCommandsInTheirWordsWithNothingLeft) {
  const fs::path dir = fresh_dir();
  // Parts large enough that merging them takes a while.
  for (const char* part : {"0/2", "1/2"}) {
    ASSERT_EQ(
        run_in(dir, {"render", "-q", "--width", "640", "--height", "480", "--spp", "2", "--depth",
                     "1", "--part", part, "-o", std::string("big") + part[0] + ".exr"})
            .exit_code,
        0);
  }
  for (const int sig : terminating_signals()) {
    SCOPED_TRACE(std::to_string(sig));
    BackgroundRender merge({"merge", (dir / "big0.exr").string(), (dir / "big1.exr").string(), "-o",
                            (dir / "m.exr").string()});
    std::this_thread::sleep_for(std::chrono::milliseconds(150));
    merge.signal(sig);
    const int code = merge.wait(30.0);
    const std::string err = merge.stderr_text();
    if (code == 0) continue;  // it finished first: nothing to see
    EXPECT_EQ(code, 128 + sig) << err;
    EXPECT_NE(err.find("rtiow: ended by signal " + std::to_string(sig)), std::string::npos) << err;
    EXPECT_EQ(leftovers(dir), "");
    fs::remove(dir / "m.exr");
  }
  // A scene being built (spheres:N): the stop is honoured within the build.
  const auto start = std::chrono::steady_clock::now();
  BackgroundRender build({"render", "-q", "--scene", "spheres:20000000", "--width", "16", "--spp",
                          "1", "-o", (dir / "field.png").string()});
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  build.signal(SIGUSR1);
  EXPECT_EQ(build.wait(60.0), 128 + SIGUSR1) << build.stderr_text();
  EXPECT_NE(build.stderr_text().find("before the render began"), std::string::npos)
      << build.stderr_text();
  EXPECT_FALSE(fs::exists(dir / "field.png"));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0)
      << "the build went on after the signal";
  EXPECT_EQ(leftovers(dir), "");
}

}  // namespace
