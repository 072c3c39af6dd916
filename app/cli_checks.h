#pragma once
// Checks of command-line values with short messages (CLI11's own range checks print the
// whole range of a double, hundreds of digits, in their error line).

#include <CLI/CLI.hpp>

#include <cmath>
#include <string>

namespace rtiow {

// A seed or count: a whole number, not negative (an unsigned option would wrap "-1").
inline const CLI::Validator kNotNegative(
    [](std::string& text) -> std::string {
      return text.find('-') == std::string::npos ? "" : "must not be negative";
    },
    "NUMBER >= 0");

// A finite number >= 0 (time limits, error targets): "inf" and "nan" are not amounts.
inline const CLI::Validator kFiniteNotNegative(
    [](std::string& text) -> std::string {
      double value = 0;
      return CLI::detail::lexical_cast(text, value) && std::isfinite(value) && value >= 0
                 ? ""
                 : "must be a finite number >= 0";
    },
    "NUMBER >= 0");

}  // namespace rtiow
