#pragma once
// --help that reads well on a terminal: an option's value is shown as its kind (INT, FLOAT,
// UINT, TEXT) or its choices ({independent,sobol,padded-sobol}), not as CLI11's parser strings
// ("UINT:NUMBER >= 0", "FLOAT:NUMBER >= 0:FLOAT in [1e-12 - 0.5]"); the ranges are in the
// descriptions, and a value outside one is refused in words. Descriptions are wrapped to the
// terminal's width ($COLUMNS, else the terminal's, else 80), beside the option's column.

#include <CLI/CLI.hpp>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

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

class ReadableHelpFormatter : public CLI::Formatter {
 public:
  std::string make_option(const CLI::Option* option, bool is_positional) const override;
  std::string make_option_opts(const CLI::Option* option) const override;
  std::string make_subcommand(const CLI::App* sub) const override;
  std::string make_description(const CLI::App* app) const override;
  std::string make_footer(const CLI::App* app) const override;
  std::string make_group(std::string group, bool is_positional,
                         std::vector<const CLI::Option*> options) const override;
};

}  // namespace rtiow
