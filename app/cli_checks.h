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

// A number from `least` to `most`, the bounds written as the help writes them (CLI11's own
// Range prints "0.000000 to 0.500000" for 1e-12 to 0.5, and only its bounds).
inline CLI::Validator from_to(double least, double most) {
  const auto shortest = [](double v) {
    char text[32];
    return std::string(text, std::to_chars(text, text + sizeof text, v).ptr);
  };
  const std::string range = shortest(least) + " to " + shortest(most);
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double value = 0;
        return CLI::detail::lexical_cast(text, value) && value >= least && value <= most
                   ? ""
                   : "must be from " + range + ", got " + text;
      },
      "NUMBER " + range);
}

}  // namespace rtiow
