#pragma once
// A failure a command reports with an exit code of its own (main prints the one line):
// `rtiow diff` keeps 1 and 2 for its verdicts, so what stops it from comparing exits 3 or 4
// as OpenImageIO's idiff does.

#include <cstdio>
#include <stdexcept>
#include <string>

#include "core/limits/error.h"

namespace rtiow {

class CommandError : public std::runtime_error {
 public:
  CommandError(const std::string& what, int exit_code)
      : std::runtime_error(what), exit_code_(exit_code) {}
  int exit_code() const { return exit_code_; }

 private:
  int exit_code_;
};

// Every message leaves as one printable line, whatever a value in it held.
inline void report_error(const std::string& what) {
  std::fprintf(stderr, "rtiow: error: %s\n", one_line(what).c_str());
}

}  // namespace rtiow
