// No threads to be had (issue 69): under a limit of processes (ulimit -u, a container's pids
// limit) every command either does its work or ends in one line that says so, with its error
// code and nothing left behind; none hangs, none ends in "internal error". The image library
// starts seven threads as it loads (on 2 cores), and one that could not start ended the process
// from inside the loader or hung joining the others.
//
// rtiow runs as a user of its own (uid 61234, which nothing else runs as, so the limit counts
// only its threads), through setpriv and prlimit: an argument vector, no shell. Needs root.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/cli_helpers.h"
#include "tests/launch.h"

namespace {

using namespace rtiow::test::cli;

constexpr const char* kUid = "61234";

struct Limited {
  int exit_code;
  std::string stderr_text;
};

Limited run_limited(const fs::path& dir, int processes, const std::vector<std::string>& args) {
  rtiow::test::Launch l;
  l.argv = {"/usr/bin/setpriv",
            std::string("--reuid=") + kUid,
            std::string("--regid=") + kUid,
            "--clear-groups",
            "/usr/bin/prlimit",
            "--nproc=" + std::to_string(processes),
            RTIOW_BINARY};
  l.argv.insert(l.argv.end(), args.begin(), args.end());
  l.directory = dir.string();
  const fs::path err = fs::path(RTIOW_TEST_OUTPUT_DIR) / (test_name() + ".limited.stderr");
  l.stderr_path = err.string();
  l.timeout_seconds = 120;
  const int code = rtiow::test::launch(l);
  return {code, slurp(err)};
}

// What is in `dir` besides `kept`, one name a line.
std::string leftovers(const fs::path& dir, const std::vector<std::string>& kept) {
  std::string found;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (std::find(kept.begin(), kept.end(), name) == kept.end()) found += name + "\n";
  }
  return found;
}

TEST(ExhaustedThreads, EveryCommandEndsInOneLineOrDoesItsWork) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to run rtiow as a user of its own";
  const fs::path dir = empty_output_dir(test_name());
  ::chmod(dir.c_str(), 0777);
  for (const std::string& input :
       {std::string("render -q --width 32 --spp 2 --stats-channels -o a.exr"),
        std::string("render -q --width 32 --spp 2 --seed 2 --stats-channels -o b.exr"),
        std::string("render -q --width 32 --spp 4 --part 0/2 -o p0.exr"),
        std::string("render -q --width 32 --spp 4 --part 1/2 -o p1.exr")}) {
    ASSERT_EQ(run_rtiow(input, dir.string()).exit_code, 0) << input;
  }
  const std::vector<std::string> inputs = {"a.exr", "b.exr", "p0.exr", "p1.exr"};
  struct Case {
    std::string args, output;
  };
  const std::vector<Case> cases = {
      {"diff a.exr b.exr", ""},
      {"merge p0.exr p1.exr -o m.exr", "m.exr"},
      {"render -q --width 32 --spp 2 -o r.exr", "r.exr"},
      {"render -q --width 32 --spp 2 --passes depth -o passes.exr", "passes.exr"},
      {"render -q --width 32 --spp 2 -o r.png", "r.png"},
  };
  for (const int processes : {2, 3, 5, 8}) {
    for (const Case& c : cases) {
      SCOPED_TRACE("ulimit -u " + std::to_string(processes) + ": rtiow " + c.args);
      const Limited r = run_limited(dir, processes, rtiow::test::words(c.args));
      ASSERT_NE(r.exit_code, 128 + 9) << "killed after 120 s: it hung\n" << r.stderr_text;
      EXPECT_EQ(r.stderr_text.find("internal error"), std::string::npos) << r.stderr_text;
      if (r.exit_code != 0) {
        EXPECT_EQ(count_lines(r.stderr_text), 1) << r.stderr_text;
        EXPECT_EQ(r.stderr_text.rfind("rtiow: error: ", 0), 0u) << r.stderr_text;
        // It says how many threads could start: the image library's ("7 threads ..., and 2
        // could start now") or the render's ("cannot start 2 threads (1 could run)").
        EXPECT_TRUE(r.stderr_text.find("could start now") != std::string::npos ||
                    r.stderr_text.find("could run") != std::string::npos)
            << r.stderr_text;
        EXPECT_FALSE(!c.output.empty() && fs::exists(dir / c.output)) << "a failed run wrote";
      }
      std::vector<std::string> kept = inputs;
      if (r.exit_code == 0 && !c.output.empty()) kept.push_back(c.output);
      EXPECT_EQ(leftovers(dir, kept), "");
      if (!c.output.empty()) fs::remove(dir / c.output);
    }
  }
  // With threads enough, each command did its work (the limit is what stopped the others).
  const Limited plenty = run_limited(dir, 64, rtiow::test::words("merge p0.exr p1.exr -o m.exr"));
  EXPECT_EQ(plenty.exit_code, 0) << plenty.stderr_text;
}

}  // namespace
