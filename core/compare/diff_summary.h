#pragma once
// `rtiow diff --summary-json FILE`: the comparison's verdict and figures for a script, in one
// documented schema (core/io/summary_json.h; diff's keys in docs/diff.md), beside the lines on
// stdout.

#include <string>
#include <vector>

#include "core/compare/image_diff.h"

namespace rtiow {

struct DiffSummary {
  std::string reference;
  std::vector<std::string> tests;
  std::string mode;  // plain, noise or seeds
  int width = 0, height = 0;
  const PlainDiff* plain = nullptr;  // the figures of the mode used
  const PlainThresholds* thresholds = nullptr;
  const NoiseDiff* noise = nullptr;
  NonFinite non_finite;
  DiffVerdict verdict = DiffVerdict::Pass;
  // Where no verdict was reached: why, and the exit code (3: images of other sizes; 4: a file
  // or option diff cannot use). The summary then says "could not compare", its figures null.
  std::string error;
  int exit_code = 0;
};

// The summary as JSON text.
std::string diff_summary_json(const DiffSummary& summary);

}  // namespace rtiow
