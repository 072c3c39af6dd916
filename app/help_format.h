#pragma once
// --help in words: an option's value is shown as its kind (INT, FLOAT, UINT, TEXT) or its
// choices ({independent,sobol,padded-sobol}), not as CLI11's parser strings
// ("UINT:NUMBER >= 0", "FLOAT:NUMBER >= 0:FLOAT in [1e-12 - 0.5]"); the ranges are in the
// descriptions, and a value outside one is refused in words.

#include <CLI/CLI.hpp>

#include <memory>
#include <string>

namespace rtiow {

// "UINT:NUMBER >= 0" -> "UINT"; "TEXT:{a,b}" -> "{a,b}".
std::string readable_type_name(const std::string& type_name);

class ReadableHelpFormatter : public CLI::Formatter {
 public:
  std::string make_option_opts(const CLI::Option* option) const override;
};

}  // namespace rtiow
