#pragma once
// The measurements' figures (what bench.json and accuracy.json hold) as the measurements keep
// them while they run, report and summarise them: nlohmann-json's documents. The one header of
// rtiow that includes nlohmann-json (core/io/json_writer.cpp writes every other JSON); the
// measurements' files compile as one unit, so the library is compiled once for them.

#include <nlohmann/json.hpp>

#include "core/io/json_writer.h"

namespace rtiow {

using Figures = nlohmann::json;

// `value` written as one value of `out`.
void write_figures(JsonWriter& out, const Figures& value);

}  // namespace rtiow
