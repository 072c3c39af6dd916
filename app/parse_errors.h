#pragma once
// CLI11's refusals in the words of what was meant: a misspelt option gets the nearest real one
// ("unknown option --widht for rtiow render; did you mean --width?"), a value of the wrong
// kind names the kind expected ("--spp expects an integer, not 'ten'"), and every hint points
// to the help of the command that was used.

#include <CLI/CLI.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace rtiow {

// The message for a parse error of `app` (after app.parse threw it).
std::string explain_parse_error(const CLI::App& app, const CLI::ParseError& error);

// The candidate nearest to `word` by edit distance (a swap of neighbours counts one), if it is
// near enough to be a likely slip (at most a third of the word, and at least 1, at most 3
// edits); empty otherwise.
std::string nearest_name(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace rtiow
