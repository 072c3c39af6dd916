#pragma once
// --quick for the measurement commands: a short run of the same measurement, for a first look
// or a check that it works, in seconds to a minute or two rather than many minutes.

#include <CLI/CLI.hpp>

#include <string>
#include <utility>
#include <vector>

namespace rtiow {

// Gives each option of `cmd` that the user did not give the quick run's value ("--repeat",
// "1"), as if it had been typed: the option's own checks apply.
inline void apply_quick_run(CLI::App& cmd,
                            const std::vector<std::pair<std::string, std::string>>& settings) {
  for (const auto& [name, value] : settings) {
    CLI::Option* option = cmd.get_option(name);
    if (option->count() > 0) continue;
    option->add_result(value);
    option->run_callback();
  }
}

}  // namespace rtiow
