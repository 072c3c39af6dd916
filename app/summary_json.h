#pragma once
// `--summary-json FILE`, one schema for every command that offers it (render, diff, bench,
// accuracy; documented in docs/usage.md, "A summary for scripts"): a JSON object that starts
// with the same keys in every command, then the command's own. The lines a command prints
// are for people; this is for a script or a benchmark harness.

#include <nlohmann/json.hpp>

#include <string>

namespace rtiow {

// Raised when a key changes meaning or goes away (new keys may be added under the same one).
inline constexpr int kSummarySchema = 1;

// {"schema", "version", "command"}: what every summary begins with.
nlohmann::ordered_json summary_head(const std::string& command);

// The summary as the file holds it: indented, ending in a newline.
std::string summary_text(const nlohmann::ordered_json& summary);

}  // namespace rtiow
