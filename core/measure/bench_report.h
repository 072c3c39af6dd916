#pragma once
// What `rtiow bench` shows and keeps: a table on stdout, the figures as JSON, a PNG plot.

#include <string>
#include "core/measure/figures.h"

namespace rtiow {

void print_bench_table(const Figures& results);

// Atomic: written to a temporary beside `path`, then renamed.
void write_bench_json(const Figures& results, const std::string& path);

// Every timed run, a row each (section, configuration, its settings, the run's figures), for a
// spreadsheet or a comparison of two machines; atomic as the JSON.
void write_bench_csv(const Figures& results, const std::string& path);

// Draws Mrays/s against N (log-log, one line per accelerator) with Debian's python3 and
// matplotlib. Without them it says so and draws nothing (returns false); the figures are in
// the JSON.
bool plot_bench(const Figures& results, const std::string& plot_path);

}  // namespace rtiow
