#pragma once
// `rtiow accuracy`'s report: the tables it prints, and the JSON, CSV and plot it writes.

#include "core/measure/accuracy_options.h"
#include "core/measure/figures.h"
#include "core/measure/measure_summary.h"

namespace rtiow {

void print_table(const Figures& figures);

// accuracy.json, accuracy.csv and accuracy.png in --out; returns the files written (the plot
// only if it was drawn).
MeasureFiles write_figures(const AccuracyOptions& o, const Figures& figures);

}  // namespace rtiow
