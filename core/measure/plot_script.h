#pragma once
// The plots are drawn by small matplotlib scripts in share/rtiow/ beside the executable's bin/
// (copied there in the build tree, installed there), run with Debian's python3 (where
// python3-matplotlib lives). No shell runs and no path is handed to the helper: it is started with
// an argument vector (the interpreter and the script), reads the figures' JSON on its standard
// input and writes the PNG on its standard output, which is the private temporary of the plot's
// output (core/io/atomic_file.h), renamed into place only when the helper succeeded and wrote a
// PNG. So any name works as --out (quotes, spaces, newlines, a leading dash) and a link at the
// plot's name is replaced, never followed.

#include <string>

namespace rtiow {

// Runs `script` (a file name in share/rtiow/) on the figures `json_text` to draw
// `png_path`. Without python3 or matplotlib it says so on stdout and draws nothing: the
// figures are still in the JSON. Returns whether the plot was drawn; throws
// std::runtime_error where matplotlib is there but the plot could not be drawn or written.
bool run_plot_script(const std::string& script, const std::string& json_text,
                     const std::string& png_path);

}  // namespace rtiow
