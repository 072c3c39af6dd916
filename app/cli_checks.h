#pragma once
// Checks of command-line values with short messages (CLI11's own range checks print the
// whole range of a double, hundreds of digits, in their error line).

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>

namespace rtiow {

// A seed: a whole number from 0 to 2^64-1 (an unsigned option would wrap "-1", and CLI11
// saturates a value beyond 2^64 instead of refusing it).
inline const CLI::Validator kNotNegative(
    [](std::string& text) -> std::string {
      if (text.find('-') != std::string::npos) return "must not be negative";
      std::uint64_t value = 0;
      const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
      return error == std::errc() && end == text.data() + text.size()
                 ? ""
                 : "must be a whole number from 0 to 2^64-1";
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

// A finite number > 0 (error targets: 0 would be a target no render reaches, and leaving the
// option out is how to ask for none).
inline const CLI::Validator kFinitePositive(
    [](std::string& text) -> std::string {
      double value = 0;
      return CLI::detail::lexical_cast(text, value) && std::isfinite(value) && value > 0
                 ? ""
                 : "must be a finite number > 0 (leave the option out for no error target)";
    },
    "NUMBER > 0");

}  // namespace rtiow
