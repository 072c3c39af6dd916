#include "core/io/summary_json.h"

#include <chrono>

#include "core/version.h"

namespace rtiow {
namespace {

// When the program started, as near as a static's initialisation comes to it.
const std::chrono::steady_clock::time_point program_start = std::chrono::steady_clock::now();

}  // namespace

nlohmann::ordered_json summary_head(const std::string& command, int exit_code) {
  nlohmann::ordered_json head;
  head["schema"] = kSummarySchema;
  head["version"] = version();
  head["command"] = command;
  head["exit_code"] = exit_code;
  head["seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - program_start).count();
  return head;
}

std::string summary_text(const nlohmann::ordered_json& summary) {
  return summary.dump(2) + "\n";
}

}  // namespace rtiow
