#pragma once
// Helper programs (the plot scripts' python3, bench's points in a process of their own) are
// started with an argument vector: no shell ever runs, so no value the user gave (an --out
// path, the program's own location) is ever read as shell text. While one runs it is
// registered to be ended with rtiow if rtiow must end at once (core/io/removed_on_abort.h).

#include <string>
#include <vector>

namespace rtiow {

struct ChildRun {
  bool started = false;
  std::string failure;  // why it could not be started, when not started
  int exit_code = -1;   // its exit status, or -1 when a signal ended it
  int signal = 0;       // the signal that ended it, or 0
  std::string output;   // its standard output, when captured
  bool ok() const { return started && exit_code == 0; }
};

// Runs `argv` (argv[0] an absolute path) and waits for it. Its standard input is `input` (fed
// whole before its output is read, so a child must read all of it first, as the plot scripts
// do); its standard output goes to `stdout_fd`, or is captured into `output` when that is -1.
// Standard error is rtiow's.
ChildRun run_child(const std::vector<std::string>& argv, const std::string& input = {},
                   int stdout_fd = -1);

}  // namespace rtiow
