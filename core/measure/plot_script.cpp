#include "core/measure/plot_script.h"

#include "core/io/child_process.h"

#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "core/io/atomic_file.h"
#include "core/limits/error.h"

namespace rtiow {
namespace {

constexpr const char* kPython = "/usr/bin/python3";

}  // namespace

bool run_plot_script(const std::string& script, const std::string& json_text,
                     const std::string& png_path) {
  namespace fs = std::filesystem;
  std::error_code error;
  // share/rtiow/ beside bin/ (RTIOW_DATADIR_FROM_BINDIR, from core/CMakeLists.txt).
  const fs::path path = fs::read_symlink("/proc/self/exe", error).parent_path() /
                        RTIOW_DATADIR_FROM_BINDIR / "rtiow" / script;
  if (!fs::exists(kPython, error) || !fs::exists(path, error)) {
    std::printf("plot: skipped (%s or %s missing)\n", kPython, one_line(path.string()).c_str());
    return false;
  }
  // The plot is optional where matplotlib is not installed; once it is, a plot that cannot be
  // written (a full disk, a file-size limit, the helper failing) is the command's failure.
  if (!run_child({kPython, "-c", "import matplotlib"}).ok()) {
    std::printf("plot: skipped (python3-matplotlib is not installed)\n");
    return false;
  }
  try {
    write_atomically(png_path, [&](int fd, std::string& reason) {
      const ChildRun run = run_child({kPython, path.string()}, json_text, fd);
      if (!run.ok()) {
        reason = run.started ? "the helper failed" : run.failure;
        return false;
      }
      // What it wrote must be a PNG (its signature), not a traceback or nothing.
      unsigned char signature[8] = {};
      if (::pread(fd, signature, sizeof signature, 0) != ssize_t(sizeof signature) ||
          std::memcmp(signature, "\x89PNG\r\n\x1a\n", sizeof signature) != 0) {
        reason = "the helper wrote no PNG";
        return false;
      }
      return true;
    });
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot draw the plot (" + one_line(path.string()) +
                             "): " + one_line(e.what()) + "; the figures are written");
  }
  std::printf("plot:    %s\n", one_line(png_path).c_str());
  return true;
}

}  // namespace rtiow
