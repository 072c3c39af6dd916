#pragma once
// The rtiow executable started in the background, for the tests that signal it or kill it.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/test_files.h"

namespace rtiow::test {

inline std::string current_test_name() {
  return ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

// A render started in the background, for the signal tests.
class BackgroundRender {
 public:
  // `ignored`: signals the render starts with ignored (as a script's background job does);
  // every other signal it catches starts at its default, whatever the test runner had.
  explicit BackgroundRender(const std::vector<std::string>& args,
                            const std::vector<int>& ignored = {}) {
    std::vector<char*> argv;
    std::string binary = RTIOW_BINARY;
    argv.push_back(binary.data());
    args_ = args;
    for (std::string& a : args_) argv.push_back(a.data());
    argv.push_back(nullptr);
    stderr_path_ =
        (std::filesystem::path(RTIOW_TEST_OUTPUT_DIR) / (current_test_name() + ".stderr")).string();
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 2, stderr_path_.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t defaults;
    sigemptyset(&defaults);
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGXCPU, SIGUSR1}) sigaddset(&defaults, sig);
    std::vector<struct sigaction> previous(ignored.size());
    for (std::size_t i = 0; i < ignored.size(); ++i) {
      sigdelset(&defaults, ignored[i]);
      struct sigaction ignore {};
      ignore.sa_handler = SIG_IGN;
      sigaction(ignored[i], &ignore, &previous[i]);  // inherited through the spawn
    }
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
    EXPECT_EQ(posix_spawn(&pid_, binary.c_str(), &actions, &attributes, argv.data(), environ), 0);
    for (std::size_t i = 0; i < ignored.size(); ++i) sigaction(ignored[i], &previous[i], nullptr);
    posix_spawnattr_destroy(&attributes);
    posix_spawn_file_actions_destroy(&actions);
  }

  void signal(int sig) const { ::kill(pid_, sig); }

  // Waits (up to 20 s) until the render has begun: it holds the locks of everything it writes
  // (`.<name>.rtiow-lock` beside the -o path, its checkpoint's and --summary-json's), taken one
  // after another once the scene is loaded and just before the render starts. A signal before
  // that ends the command before any work, as it should, but would test nothing of a render's
  // stop. A render with no -o: until it catches SIGINT.
  bool wait_until_rendering() const {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    std::vector<std::string> locks;
    const auto lock_of = [](const std::filesystem::path& out, const char* suffix) {
      std::string name = ".";  // appended: GCC 12 warns falsely (-Wrestrict) on "." + ...
      name.append(out.filename().string()).append(suffix).append(".rtiow-lock");
      return (out.parent_path() / name).string();
    };
    for (std::size_t i = 0; i + 1 < args_.size(); ++i) {
      if (args_[i] == "-o" || args_[i] == "--output") {
        locks.push_back(lock_of(args_[i + 1], ""));
        locks.push_back(lock_of(args_[i + 1], ".rtiow-checkpoint"));
      } else if (args_[i] == "--summary-json") {
        locks.push_back(lock_of(args_[i + 1], ""));
      }
    }
    const std::string status_path = "/proc/" + std::to_string(pid_) + "/status";
    while (std::chrono::steady_clock::now() < deadline) {
      // A lock is taken once its holder's pid is in it (it exists a moment before, while
      // rtiow still checks it is the file it locked).
      const auto taken = [](const std::string& lock) {
        std::error_code no_file;
        return std::filesystem::file_size(lock, no_file) > 0 && !no_file;
      };
      if (!locks.empty() && std::all_of(locks.begin(), locks.end(), taken)) return true;
      std::ifstream status(status_path);
      std::string line;
      while (locks.empty() && std::getline(status, line)) {
        if (line.rfind("SigCgt:", 0) == 0) {
          const unsigned long long caught = std::stoull(line.substr(7), nullptr, 16);
          if (caught & (1ull << (SIGINT - 1))) return true;
        }
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return false;
  }

  // The exit code, or -1 if it did not end within `seconds` (then it is killed).
  int wait(double seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    int status = 0;
    while (std::chrono::steady_clock::now() < deadline) {
      if (waitpid(pid_, &status, WNOHANG) == pid_)
        return WIFEXITED(status) ? WEXITSTATUS(status) : -2;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ::kill(pid_, SIGKILL);
    waitpid(pid_, &status, 0);
    return -1;
  }

  std::string stderr_text() const { return slurp(stderr_path_); }
  pid_t pid() const { return pid_; }

 private:
  std::vector<std::string> args_;
  std::string stderr_path_;
  pid_t pid_ = -1;
};

}  // namespace rtiow::test
