#pragma once
// How the command line speaks (app/command_text.cpp, with app/command_line.cpp the only files
// that see CLI11).
// --help that reads well on a terminal: an option's value is shown as its kind (INT, FLOAT,
// UINT, TEXT) or its choices ({independent,sobol,padded-sobol}), not as CLI11's parser strings
// ("UINT:NUMBER >= 0", "FLOAT:NUMBER >= 0:FLOAT in [1e-12 - 0.5]"); the ranges are in the
// descriptions, and a value outside one is refused in words. Descriptions are wrapped to the
// terminal's width ($COLUMNS, else the terminal's, else 80), beside the option's column.
//
// CLI11's refusals in the words of what was meant: a misspelt option gets the nearest real one
// ("unknown option --widht for rtiow render; did you mean --width?"), a value of the wrong
// kind names the kind expected ("--spp expects an integer, not 'ten'"), and every hint points
// to the help of the command that was used.

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace CLI {
class App;
class FormatterBase;
class ParseError;
}  // namespace CLI

namespace rtiow {

// "UINT:NUMBER >= 0" -> "UINT"; "TEXT:{a,b}" -> "{a,b}".
std::string readable_type_name(const std::string& type_name);

// The width help is wrapped to: $COLUMNS if it holds a number from 40 to 1000, else standard
// output's terminal width, else 80.
std::size_t help_width();

// `left` in a column of `column` characters (two spaces in), then `text` wrapped at `width`,
// its continuation lines indented to the column; a `left` too wide for its column puts the
// text on the next line.
std::string wrap_beside(const std::string& left, const std::string& text, std::size_t column,
                        std::size_t width);

// The formatter of every command's --help.
std::shared_ptr<CLI::FormatterBase> readable_help_formatter();

// Every spelling of a command's own options: --long and -s.
std::vector<std::string> option_spellings(const CLI::App& command);

// The message for a parse error of `app` (after app.parse threw it).
std::string explain_parse_error(const CLI::App& app, const CLI::ParseError& error);

}  // namespace rtiow
