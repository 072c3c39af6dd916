// MPI rendering (built when OpenMPI is installed): mpirun -np 2 and -np 3 give the file one
// process gives, byte for byte, variance channels included; a rank that dies ends the run instead
// of hanging it; bad input, a misspelt option and --help are printed once.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

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

// Runs a shell command; returns its exit code, stderr in `err`.
int run(const std::string& command, std::string* err = nullptr) {
  const fs::path err_path = output("stderr.txt");
  const int status = std::system((command + " 2> " + err_path.string()).c_str());
  if (err) *err = slurp(err_path);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
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
  EXPECT_EQ(run(mpirun(2) + kRender + " --help > " + help.string()), 0);
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
  const std::string command = mpirun(2) + std::string(RTIOW_BINARY) +
                              " render --scene cover --width 200 --spp 100000 --seed 9042001 "
                              "--threads 1 -q -o " +
                              out.string() + " 2>/dev/null";
  const auto start = std::chrono::steady_clock::now();
  std::thread killer([] {
    std::this_thread::sleep_for(std::chrono::seconds(2));
    // Only the ranks' command lines start with the binary (not mpirun's, timeout's or this
    // shell's), and only theirs hold this seed (not another test's render, running beside this
    // one under ctest -j); the [1] keeps the pattern from matching itself.
    const std::string pattern = "^" + std::string(RTIOW_BINARY) +
                                " render --scene cover --width 200 --spp 100000 " +
                                "--seed 904200[1]";
    std::system(("kill -9 $(pgrep -f '" + pattern + "' | tail -1)").c_str());
  });
  const int status = std::system(("timeout 60 " + command).c_str());
  killer.join();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) != 0);
  EXPECT_NE(WEXITSTATUS(status), 124) << "mpirun hung until the timeout";
  EXPECT_LT(seconds, 30.0);
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
