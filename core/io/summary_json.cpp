#include "core/io/summary_json.h"

#include <chrono>

#include "core/version.h"

namespace rtiow {
namespace {

// When the program started, as near as a static's initialisation comes to it.
const std::chrono::steady_clock::time_point program_start = std::chrono::steady_clock::now();

// The summaries' indentation (nlohmann-json's dump(2) layout).
constexpr int kSummaryIndent = 2;

}  // namespace

Metadata summary_head(const std::string& command, int exit_code) {
  return {
      {"schema", std::int64_t(kSummarySchema)},
      {"version", std::string(version())},
      {"command", command},
      {"exit_code", std::int64_t(exit_code)},
      {"seconds",
       std::chrono::duration<double>(std::chrono::steady_clock::now() - program_start).count()}};
}

JsonWriter begin_summary(const std::string& command, int exit_code) {
  JsonWriter summary(kSummaryIndent);
  summary.begin_object().members(summary_head(command, exit_code));
  return summary;
}

std::string summary_text(JsonWriter& summary) {
  summary.end();
  return summary.text() + "\n";
}

}  // namespace rtiow
