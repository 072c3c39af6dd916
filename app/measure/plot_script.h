#pragma once
// The plots are drawn by small matplotlib scripts copied beside the executable at build
// time, run with Debian's python3 (where python3-matplotlib lives).

#include <string>

namespace rtiow {

// Runs `script` (a file name beside the executable) on the JSON figures to draw `png_path`.
// Without python3 or matplotlib it says so on stdout and draws nothing: the figures are
// still in the JSON. Returns whether the plot was drawn.
bool run_plot_script(const std::string& script, const std::string& json_path,
                     const std::string& png_path);

}  // namespace rtiow
