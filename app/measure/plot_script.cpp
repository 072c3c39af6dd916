#include "app/measure/plot_script.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "core/limits/error.h"

namespace rtiow {

bool run_plot_script(const std::string& script, const std::string& json_path,
                     const std::string& png_path) {
  namespace fs = std::filesystem;
  const fs::path path = fs::read_symlink("/proc/self/exe").parent_path() / script;
  const char* python = "/usr/bin/python3";
  if (!fs::exists(python) || !fs::exists(path)) {
    std::printf("plot: skipped (%s or %s missing)\n", python, path.c_str());
    return false;
  }
  const std::string command =
      std::string(python) + " '" + path.string() + "' '" + json_path + "' '" + png_path + "'";
  if (std::system(command.c_str()) != 0) {
    std::printf("plot: skipped (%s failed; is python3-matplotlib installed?)\n", path.c_str());
    return false;
  }
  std::printf("plot:    %s\n", one_line(png_path).c_str());
  return true;
}

}  // namespace rtiow
