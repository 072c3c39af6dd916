#pragma once
// The one way the tests start a program: an argument vector, never a shell (rtiow's own rule
// for itself), in a directory of the test's choosing, with variables added to its environment
// and each standard stream from a file, /dev/null, closed, or (stdout) a pipe whose reader
// leaves early. posix_spawn, so nothing of the test runs between fork and exec; a time limit
// kills the program rather than hanging the suite.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace rtiow::test {

struct Launch {
  std::vector<std::string> argv;         // argv[0] is the program, found on PATH if no '/'
  std::string directory;                 // empty: the test's own
  std::vector<std::string> environment;  // "NAME=value", added to the test's
  // Each stream: a path to open (stdin for reading, the others truncated for writing), or
  // empty: closed.
  std::string stdin_path = "/dev/null";
  std::string stdout_path = "/dev/null";
  std::string stderr_path = "/dev/null";
  // Zero or more: stdout is a pipe whose reader takes this many bytes and leaves (a `| head
  // -c N`); stdout_path is then ignored.
  long stdout_reader_bytes = -1;
  double timeout_seconds = 300;  // then SIGKILL, and 128 + 9
};

// Words separated by spaces, as a shell splits a line without quotes or expansions: how the
// tests write a command line they build from parts.
inline std::vector<std::string> words(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  for (std::string word; in >> word;) out.push_back(word);
  return out;
}

// Runs the program to its end: its exit code, 128 + the signal that ended it, or 127 when it
// could not be started.
inline int launch(const Launch& l) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  const auto stream = [&](int fd, const std::string& path, int flags) {
    if (path.empty()) {
      posix_spawn_file_actions_addclose(&actions, fd);
    } else {
      posix_spawn_file_actions_addopen(&actions, fd, path.c_str(), flags, 0644);
    }
  };
  int pipe_fds[2] = {-1, -1};
  stream(0, l.stdin_path, O_RDONLY);
  if (l.stdout_reader_bytes >= 0) {
    if (pipe2(pipe_fds, O_CLOEXEC) != 0) return 127;
    posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], 1);
  } else {
    stream(1, l.stdout_path, O_WRONLY | O_CREAT | O_TRUNC);
  }
  stream(2, l.stderr_path, O_WRONLY | O_CREAT | O_TRUNC);
  if (!l.directory.empty()) posix_spawn_file_actions_addchdir_np(&actions, l.directory.c_str());

  std::vector<std::string> env_strings;
  for (char** e = environ; *e; ++e) env_strings.emplace_back(*e);
  for (const std::string& added : l.environment) {
    const std::string name = added.substr(0, added.find('=') + 1);
    std::erase_if(env_strings, [&](const std::string& e) { return e.rfind(name, 0) == 0; });
    env_strings.push_back(added);
  }
  std::vector<char*> env, argv;
  for (std::string& e : env_strings) env.push_back(e.data());
  env.push_back(nullptr);
  std::vector<std::string> args = l.argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), env.data());
  posix_spawn_file_actions_destroy(&actions);
  if (pipe_fds[1] >= 0) close(pipe_fds[1]);
  if (spawned != 0) {
    if (pipe_fds[0] >= 0) close(pipe_fds[0]);
    return 127;
  }
  if (pipe_fds[0] >= 0) {  // the reader that leaves early
    char buffer[4096];
    long left = l.stdout_reader_bytes;
    while (left > 0) {
      const ssize_t got = read(pipe_fds[0], buffer, std::size_t(std::min<long>(left, 4096)));
      if (got <= 0) break;
      left -= got;
    }
    close(pipe_fds[0]);
  }
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(l.timeout_seconds);
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 127;
}

}  // namespace rtiow::test
