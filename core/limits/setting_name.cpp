#include "core/limits/setting_name.h"

namespace rtiow {
namespace {

std::string library_spelling(std::string_view name, std::string_view value) {
  std::string text(name);
  if (!value.empty()) text.append("=").append(value);
  return text;
}

SettingSpeller speller = library_spelling;

}  // namespace

void spell_settings_as(SettingSpeller s) {
  speller = s ? s : library_spelling;
}

std::string setting(std::string_view name, std::string_view value) {
  return speller(name, value);
}

}  // namespace rtiow
