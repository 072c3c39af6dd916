#pragma once
// Checks of command-line values with short messages (CLI11's own range checks print the
// whole range of a double, hundreds of digits, in their error line).

#include <CLI/CLI.hpp>

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>

#include "core/limits/number_text.h"

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
  const std::string range = shortest_text(least) + " to " + shortest_text(most);
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double value = 0;
        return CLI::detail::lexical_cast(text, value) && value >= least && value <= most
                   ? ""
                   : "must be from " + range + ", got " + text;
      },
      "NUMBER " + range);
}

// A whole number as a user writes it: decimal. CLI11 reads "010" as octal 8 and "0x10" as
// sixteen; every whole-number option takes leading zeros as decimal and refuses another base.
// A transform, so that it runs before the option's own checks and conversion.
inline const CLI::Validator kDecimal(
    [](std::string& text) -> std::string {
      const std::size_t at = !text.empty() && (text[0] == '+' || text[0] == '-') ? 1 : 0;
      if (text.size() > at + 1 && text[at] == '0' && std::isalpha(std::uint8_t(text[at + 1]))) {
        return "'" + text + "' is not a decimal number";
      }
      std::size_t zeros = at;
      while (zeros + 1 < text.size() && text[zeros] == '0' &&
             std::isdigit(std::uint8_t(text[zeros + 1]))) {
        ++zeros;
      }
      text.erase(at, zeros - at);
      return "";
    },
    "");

// Gives every whole-number option of `app` and its commands kDecimal.
inline void read_whole_numbers_as_decimal(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    const std::string type = option->get_type_name();
    if (type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0) option->transform(kDecimal);
  }
  for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    read_whole_numbers_as_decimal(*command);
  }
}

}  // namespace rtiow
