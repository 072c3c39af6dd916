#pragma once
// `rtiow accuracy`'s report: the tables it prints, and the JSON, CSV and plot it writes.

#include <nlohmann/json.hpp>

#include "app/measure/accuracy_options.h"

namespace rtiow {

void print_table(const nlohmann::json& figures);

// accuracy.json, accuracy.csv and accuracy.png in --out.
void write_figures(const AccuracyOptions& o, const nlohmann::json& figures);

}  // namespace rtiow
