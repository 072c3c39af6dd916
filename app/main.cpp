// rtiow: the command line. Parses, dispatches to a subcommand, and turns every refusal
// into one line on stderr with exit code 2 (bad input) or 1 (a failure while working).

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <functional>
#include <iostream>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/command_error.h"
#include "app/command_line.h"
#include "app/interrupt.h"
#include "app/mpi_launch.h"
#include "app/mpi_session.h"
#include "app/source_commit.h"
#include "core/io/removed_on_abort.h"
#include "core/limits/error.h"
#include "core/limits/setting_name.h"
#include "core/version.h"

namespace {

void report(const std::string& what) {
  rtiow::report_error(what);
}

// `rtiow --version`: the version, then what was built in, a fact a line.
std::string version_text() {
  std::string text = std::string("rtiow ") + rtiow::version();
  text.append("\ncommit: ").append(rtiow::source_commit());
  for (const std::string& fact : rtiow::build_facts()) text.append("\n").append(fact);
  return text.append("\n").append(rtiow::mpi_build_fact());
}

// The last guard: should an exception escape where none may (a noexcept frame, or a library's
// initialiser throwing through dlopen, as one of the image library's dependencies does when it
// cannot start a thread under a memory limit), say so in one line, naming it, and exit 1
// rather than print terminate's text and abort. No image is half-written (images are written
// whole and renamed); a checkpoint already saved stays.
[[noreturn]] void on_terminate() {
  rtiow::remove_files_now();  // the lock and any temporary: nothing left behind
  try {
    std::string what = "an unknown exception";
    if (const std::exception_ptr escaped = std::current_exception()) {
      try {
        std::rethrow_exception(escaped);
      } catch (const std::exception& e) {
        what = e.what();
      } catch (...) {
      }
    }
    std::fprintf(stderr,
                 "rtiow: error: internal error: an exception escaped (%s); no image was written\n",
                 rtiow::one_line(what, 200).c_str());
  } catch (...) {  // no memory even for the message's text
    std::fputs("rtiow: error: internal error: an exception escaped; no image was written\n",
               stderr);
  }
  std::_Exit(1);
}

// Runs the command that was parsed; every failure leaves as one line: exit 2 for bad input,
// 1 for a failure while working.
int run_command(const rtiow::CommandLine& c, const rtiow::MpiSession& mpi) {
  using rtiow::Command;
  switch (c.command) {
    case Command::Render:
      return rtiow::run_render_command(c.render, mpi);
    case Command::Scene:
      return rtiow::run_scene(c.scene);
    case Command::Merge:
      return rtiow::run_merge(c.merge);
    case Command::Denoise:
      return rtiow::run_merge(c.denoise);
    case Command::Bench:
      return rtiow::run_bench_command(c.bench);
    case Command::BenchPoint:
      return rtiow::run_bench_point(c.point);
    case Command::Accuracy:
      return rtiow::run_accuracy_command(c.accuracy);
    case Command::Diff:
      return rtiow::run_diff_command(c.diff);
  }
  return 0;
}

int run_parsed_command(const rtiow::CommandLine& command, const rtiow::MpiSession& mpi) {
  try {
    return run_command(command, mpi);
  } catch (const rtiow::CommandError& e) {  // a command's own exit code
    if (mpi.rank() == 0) report(e.what());
    return e.exit_code();
  } catch (const rtiow::InvalidInput& e) {
    // Bad input is seen alike by every rank before any work: say it once, all exit.
    if (mpi.rank() == 0) report(e.what());
    return 2;
  } catch (const std::exception& e) {
    const bool memory = dynamic_cast<const std::bad_alloc*>(&e) != nullptr;
    const std::string what = memory ? "out of memory; nothing was written" : e.what();
    if (mpi.distributed()) {
      std::fprintf(stderr, "rtiow: error on rank %d of %d: %s\n", mpi.rank(), mpi.size(),
                   rtiow::one_line(what).c_str());
      mpi.abort(1);  // the other ranks may be waiting for this one
    }
    report(what.c_str());
    return 1;
  } catch (...) {
    report("internal error (an unknown exception); nothing was written");
    return 1;
  }
  return 0;
}

// A launcher may start rtiow with descriptors 0-2 closed: the first files rtiow opens would
// take those numbers, and text meant for stderr would land in an image. Hold each number
// with /dev/null opened read-only (open takes the lowest free number, so each fills its
// own): reading gives nothing, and writing fails as it would on the closed descriptor, so a
// table printed to a closed stdout is still reported lost.
void hold_standard_descriptors() {
  for (int fd = 0; fd <= 2; ++fd) {
    if (::fcntl(fd, F_GETFD) == -1 && errno == EBADF) {
      if (::open("/dev/null", O_RDONLY) != fd) std::_Exit(1);
    }
  }
}

// What a command printed must have reached standard output: a full disk, a closed pipe
// (`| head -1`) or a closed descriptor turn success into exit 1 with one line. (A command
// that failed has said why already, and exits non-zero.)
// What a command printed is part of its result: lost, it is an error in one line. A command
// that failed has said why already; diff's 1 and 2 are verdicts, not failures, which a script
// would take as given though their text is gone: a lost verdict is diff's "could not
// compare" (4).
int check_standard_output(int code, bool diff) {
  const bool verdict = diff && (code == 1 || code == 2);
  if (code != 0 && !verdict) return code;
  errno = 0;
  const bool flushed = std::fflush(stdout) == 0;
  if (flushed && !std::ferror(stdout)) return code;
  const std::string why = !flushed && errno != 0
                              ? std::strerror(errno)
                              : "a closed descriptor, a closed pipe or a full disk";
  report(("cannot write to standard output (" + why + "): what was printed is lost").c_str());
  return diff ? rtiow::kDiffCouldNotCompare : 1;
}

}  // namespace

// bench's points, run in processes of their own (bench-point --helper): a Ctrl-C reaches them
// too, and bench says what it did.
bool is_bench_helper(int argc, char** argv) {
  return argc > 2 && std::string_view(argv[1]) == "bench-point" &&
         std::any_of(argv + 2, argv + argc,
                     [](const char* a) { return std::string_view(a) == "--helper"; });
}

// The library's setting names as this command line spells its options: "--min-spp 2".
std::string command_line_setting(std::string_view name, std::string_view value) {
  std::string text = name == "output" ? "-o/--" : "--";
  for (const char c : name) text.push_back(c == '_' ? '-' : c);
  if (!value.empty()) text.append(" ").append(value);
  return text;
}

int main(int argc, char** argv) {
  hold_standard_descriptors();
  rtiow::spell_settings_as(command_line_setting);
  // Quiet from the first instant, before a signal can find a helper parsing.
  if (is_bench_helper(argc, argv)) rtiow::end_quietly_on_signals();
  // A signal ends rtiow in its own words, with no temporary left (a render stops gracefully
  // first: app/interrupt.h).
  rtiow::end_at_once_on_signals();
  std::set_terminate(on_terminate);
  // A closed pipe is an error to report (exit 1), not a signal that kills silently.
  std::signal(SIGPIPE, SIG_IGN);
  // Likewise a file-size limit: the write fails (EFBIG), the target is left as it was.
  std::signal(SIGXFSZ, SIG_IGN);
  // A build without MPI under mpirun would render the whole image in every process.
  const rtiow::EnvironmentLookup environment = [](const char* name) { return std::getenv(name); };
  if (const std::string why = rtiow::launch_refusal(rtiow::kBuiltWithMpi, environment);
      !why.empty()) {
    if (rtiow::first_of_launch(environment)) report(why.c_str());
    return 2;
  }
  const rtiow::MpiSession mpi(argc, argv);
  rtiow::CommandLine command;
  if (const std::optional<int> code =
          rtiow::parse_command_line(argc, argv, version_text(), mpi.rank() == 0, command)) {
    return *code;
  }
  return check_standard_output(run_parsed_command(command, mpi),
                               argc > 1 && std::string_view(argv[1]) == "diff");
}
