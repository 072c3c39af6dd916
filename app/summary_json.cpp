#include "app/summary_json.h"

#include "core/version.h"

namespace rtiow {

nlohmann::ordered_json summary_head(const std::string& command) {
  nlohmann::ordered_json head;
  head["schema"] = kSummarySchema;
  head["version"] = version();
  head["command"] = command;
  return head;
}

std::string summary_text(const nlohmann::ordered_json& summary) {
  return summary.dump(2) + "\n";
}

}  // namespace rtiow
