// MPI rendering (built when OpenMPI is installed): mpirun -np 2 and -np 3 give the file one
// process gives, byte for byte, variance channels included; a rank that dies ends the run instead
// of hanging it; bad input, a misspelt option and --help are printed once.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/launch.h"
#include "tests/test_files.h"

namespace {

namespace fs = std::filesystem;

using rtiow::test::slurp;

// CTest runs these tests in parallel processes: each test gets its own files.
fs::path output(const std::string& name) {
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const fs::path p = fs::path(RTIOW_TEST_OUTPUT_DIR) / ("mpi-" + test + "-" + name);
  fs::remove(p);
  return p;
}

// Runs a command line (split at spaces, no shell): its exit code, stderr in `err`, stdout to
// `stdout_path`.
int run(const std::string& command, std::string* err = nullptr,
        const std::string& stdout_path = "/dev/null", double timeout_seconds = 300) {
  const fs::path err_path = output("stderr.txt");
  rtiow::test::Launch launch;
  launch.argv = rtiow::test::words(command);
  launch.stdout_path = stdout_path, launch.stderr_path = err_path.string();
  launch.timeout_seconds = timeout_seconds;
  const int code = rtiow::test::launch(launch);
  if (err) *err = slurp(err_path);
  return code;
}

// The process, other than this one, whose command line begins with `words`; the newest if
// several (0 if none).
pid_t process_running(const std::vector<std::string>& words) {
  pid_t found = 0;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const auto pid = pid_t(std::stol(name));
    if (pid == getpid()) continue;
    std::ifstream in(entry.path() / "cmdline", std::ios::binary);
    std::vector<std::string> args;
    for (std::string arg; std::getline(in, arg, '\0');) args.push_back(arg);
    if (args.size() >= words.size() && std::equal(words.begin(), words.end(), args.begin())) {
      found = std::max(found, pid);
    }
  }
  return found;
}

std::string mpirun(int ranks) {
  // Tests may run as root (CI): OpenMPI refuses that unless told it is intended.
  setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  return std::string(RTIOW_MPIEXEC) + " --oversubscribe -np " + std::to_string(ranks) + " ";
}

const std::string kRender =
    std::string(RTIOW_BINARY) +
    " render --scene cover --width 96 --spp 7 --threads 1 --reproducible -q";

TEST(Mpi, RanksGiveTheSingleProcessFileByteForByte) {
  const fs::path single = output("single.png");
  ASSERT_EQ(run(kRender + " -o " + single.string()), 0);
  for (int ranks : {2, 3}) {
    const fs::path distributed = output("ranks" + std::to_string(ranks) + ".png");
    std::string err;
    ASSERT_EQ(run(mpirun(ranks) + kRender + " -o " + distributed.string(), &err), 0) << err;
    EXPECT_EQ(slurp(distributed), slurp(single)) << ranks << " ranks";
  }
  // And the variances: the ranks' exact spreads add up to one process's.
  const fs::path single_stats = output("single-stats.exr");
  ASSERT_EQ(run(kRender + " --stats-channels -o " + single_stats.string()), 0);
  const fs::path distributed_stats = output("ranks-stats.exr");
  std::string err;
  ASSERT_EQ(run(mpirun(2) + kRender + " --stats-channels -o " + distributed_stats.string(), &err),
            0)
      << err;
  EXPECT_EQ(slurp(distributed_stats), slurp(single_stats)) << "the variance channels differ";
}

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t count = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++count;
  }
  return count;
}

TEST(Mpi, BadInputIsReportedOnce) {
  std::string err;
  EXPECT_NE(run(mpirun(2) + kRender + " --vfov 0 -o " + output("bad.png").string(), &err), 0);
  EXPECT_EQ(occurrences(err, "rtiow: error"), 1u) << err;
  EXPECT_FALSE(fs::exists(output("bad.png")));
  // A misspelt option, an unknown command and --help: every rank parses them, one speaks.
  for (const std::string& args : {kRender + " --sp 4", std::string(RTIOW_BINARY) + " rendr"}) {
    EXPECT_NE(run(mpirun(2) + args, &err), 0);
    EXPECT_EQ(occurrences(err, "rtiow: error"), 1u) << args << "\n" << err;
  }
  const fs::path help = output("help.txt");
  EXPECT_EQ(run(mpirun(2) + kRender + " --help", nullptr, help.string()), 0);
  EXPECT_EQ(occurrences(slurp(help), "Usage: rtiow render"), 1u) << slurp(help);
}

// A crop under mpirun: the ranks share its samples, and the file is one process's.
// A crop with the passes: the ranks' pass sums add to one process's too.
TEST(Mpi, ACropIsTheSingleProcessCrop) {
  const fs::path single = output("crop-single.exr"), distributed = output("crop-ranks.exr");
  const std::string crop = kRender + " --crop 20,10,70,40 --passes albedo,normal,depth -o ";
  ASSERT_EQ(run(crop + single.string()), 0);
  std::string err;
  ASSERT_EQ(run(mpirun(2) + crop + distributed.string(), &err), 0) << err;
  const std::string a = slurp(single);
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, slurp(distributed)) << "files differ";
}

TEST(Mpi, ARankThatDiesEndsTheRun) {
  const fs::path out = output("killed.png");
  const std::string rank =
      std::string(RTIOW_BINARY) + " render --scene cover --width 200 --spp 100000 --seed 9042001";
  const auto start = std::chrono::steady_clock::now();
  std::thread killer([&] {
    std::this_thread::sleep_for(std::chrono::seconds(2));
    // Only the ranks' command lines start with the binary (not mpirun's), and only theirs hold
    // this seed (not another test's render, running beside this one under ctest -j).
    if (const pid_t pid = process_running(rtiow::test::words(rank))) kill(pid, SIGKILL);
  });
  const int code =
      run(mpirun(2) + rank + " --threads 1 -q -o " + out.string(), nullptr, "/dev/null", 60);
  killer.join();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(code, 0);  // mpirun's own 137 for a rank killed: the launcher's limit is 60 s
  EXPECT_LT(seconds, 30.0) << "mpirun hung after a rank died";
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
