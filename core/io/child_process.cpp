#include "core/io/child_process.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/io/file_bytes.h"
#include "core/io/removed_on_abort.h"

extern char** environ;

namespace rtiow {
namespace {

// A pipe whose ends close with it.
struct Pipe {
  int read = -1, write = -1;
  bool open() {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) return false;
    read = fds[0], write = fds[1];
    return true;
  }
  static void close_end(int& fd) {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
  ~Pipe() {
    close_end(read);
    close_end(write);
  }
};

}  // namespace

ChildRun run_child(const std::vector<std::string>& argv, const std::string& input, int stdout_fd) {
  ChildRun run;
  Pipe in, out;
  if (!in.open() || (stdout_fd < 0 && !out.open())) {
    run.failure = std::string("no pipe: ") + std::strerror(errno);
    return run;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in.read, STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, stdout_fd >= 0 ? stdout_fd : out.write, STDOUT_FILENO);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  const int spawned =
      ::posix_spawn(&pid, argv.at(0).c_str(), &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  Pipe::close_end(in.read);
  Pipe::close_end(out.write);
  if (spawned != 0) {
    run.failure = "cannot start " + argv[0] + ": " + std::strerror(spawned);
    return run;
  }
  run.started = true;
  const EndedOnAbort ended_with_rtiow(pid);
  std::string ignored;
  write_all(in.write, input.data(), input.size(), ignored);  // a child that stops reading: EPIPE
  Pipe::close_end(in.write);
  if (out.read >= 0) {
    char buffer[4096];
    for (;;) {
      const ssize_t n = ::read(out.read, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      run.output.append(buffer, std::size_t(n));
    }
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) run.signal = WTERMSIG(status);
  return run;
}

}  // namespace rtiow
