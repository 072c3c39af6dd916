#pragma once
// CLI11's refusals in the words of what was meant: a misspelt option gets the nearest real one
// ("unknown option --widht for rtiow render; did you mean --width?"), a value of the wrong
// kind names the kind expected ("--spp expects an integer, not 'ten'"), and every hint points
// to the help of the command that was used.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace rtiow {

// Every spelling of a command's own options: --long and -s.
std::vector<std::string> option_spellings(const CLI::App& command);

// The message for a parse error of `app` (after app.parse threw it).
std::string explain_parse_error(const CLI::App& app, const CLI::ParseError& error);

}  // namespace rtiow
