#pragma once
// The measurements' figures (what bench.json and accuracy.json hold) as the measurements keep
// them while they run, report and summarise them: nlohmann-json's documents. The one header of
// rtiow that includes nlohmann-json (core/io/json_writer.cpp writes every other JSON); the
// measurements' files compile as one unit, so the library is compiled once for them.

#include <nlohmann/json.hpp>

#include "core/io/json_writer.h"

namespace rtiow {

using Figures = nlohmann::json;

// `value` as JSON text (nlohmann-json's dump(indent)), a string's bytes that are not UTF-8 each
// written as U+FFFD: JSON holds only UTF-8, and a path named in another encoding (a cache or
// output directory) must not end a measurement in the library's exception with its work unsaved.
std::string figures_text(const Figures& value, int indent = -1);

// `value` written as one value of `out`.
void write_figures(JsonWriter& out, const Figures& value);

}  // namespace rtiow
