#pragma once
// `--summary-json FILE`, one schema for every command that offers it (render, diff, bench,
// accuracy; documented in docs/usage.md, "A summary for scripts"): a JSON object that starts
// with the same keys in every command, then the command's own. The lines a command prints
// are for people; this is for a script or a benchmark harness.

#include <nlohmann/json.hpp>

#include <string>

namespace rtiow {

// Raised when a key changes meaning or goes away (new keys may be added under the same one).
// 2: `seconds` is the whole command's time in every command (render's sample loop moved to
// `render_seconds`), `error` is every render's estimate with the target in `error.target`.
// docs/summary.schema.json publishes it; the tests validate every command's summary against it.
inline constexpr int kSummarySchema = 2;

// {"schema", "version", "command", "exit_code", "seconds"}: what every summary begins with;
// `seconds` the command's time so far (since the program started).
nlohmann::ordered_json summary_head(const std::string& command, int exit_code);

// The summary as the file holds it: indented, ending in a newline.
std::string summary_text(const nlohmann::ordered_json& summary);

}  // namespace rtiow
