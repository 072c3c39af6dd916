#pragma once
// `rtiow bench --summary-json FILE` and `rtiow accuracy --summary-json FILE`: the measurement's
// headline figures in the summary schema every command shares (core/io/summary_json.h; the keys
// in docs/usage.md), beside the full figures (bench.json, accuracy.json) and the table.

#include <memory>
#include <string>
#include <vector>
#include "core/measure/figures.h"

namespace rtiow {

class OutputClaim;

// --summary-json checked and claimed before the measurement's minutes of work, so a path it
// cannot write is refused at once (core/io/output_claim.h); null when none was asked for.
std::unique_ptr<OutputClaim> claim_summary(const std::string& path);

// The files the measurement wrote; a plot is listed only if it was drawn.
struct MeasureFiles {
  std::string figures;
  std::string csv;  // accuracy only
  std::string plot;
};

// `results` is what bench.json holds.
std::string bench_summary_json(const Figures& results, const MeasureFiles& files);

// `results` is what accuracy.json holds.
std::string accuracy_summary_json(const Figures& results, const MeasureFiles& files);

}  // namespace rtiow
