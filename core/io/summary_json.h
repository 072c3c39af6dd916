#pragma once
// `--summary-json FILE`, one schema for every command that offers it (render, diff, bench,
// accuracy; documented in docs/usage.md, "A summary for scripts"): a JSON object that starts
// with the same keys in every command, then the command's own. The lines a command prints
// are for people; this is for a script or a benchmark harness.

#include <string>

#include "core/io/image_output.h"
#include "core/io/json_writer.h"

namespace rtiow {

// Raised when a key changes meaning or goes away (new keys may be added under the same one).
// 2: `seconds` is the whole command's time in every command (render's sample loop moved to
// `render_seconds`), `error` is every render's estimate with the target in `error.target`.
// docs/summary.schema.json publishes it; the tests validate every command's summary against it.
inline constexpr int kSummarySchema = 2;

// {"schema", "version", "command", "exit_code", "seconds"}: what every summary begins with;
// `seconds` the command's time so far (since the program started).
Metadata summary_head(const std::string& command, int exit_code);

// A summary's writer, its object begun with the head: the command adds its own members.
JsonWriter begin_summary(const std::string& command, int exit_code);

// The summary as the file holds it: indented, ending in a newline (`summary`'s object ended).
std::string summary_text(JsonWriter& summary);

}  // namespace rtiow
