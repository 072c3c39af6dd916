#pragma once
// `rtiow merge PART... -o OUT`: adds shares of one render (from --sample-range or --part)
// into the image a single render would have produced.

#include <string>
#include <vector>

namespace rtiow {

struct MergeOptions {
  std::string command = "merge";  // or "denoise": the same work, denoised
  std::vector<std::string> parts;
  std::string output;
  bool stats_channels = false;
  bool denoise = false;
  bool quiet = false;
  int threads = 0;           // 0: every core
  std::string summary_json;  // --summary-json: where the summary goes, or empty
};

int run_merge(const MergeOptions& o);

}  // namespace rtiow
