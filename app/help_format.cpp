#include "app/help_format.h"

namespace rtiow {

std::string readable_type_name(const std::string& type_name) {
  const std::size_t choices = type_name.find(":{");
  if (choices != std::string::npos) {
    return type_name.substr(choices + 1, type_name.find('}', choices) - choices);
  }
  return type_name.substr(0, type_name.find(':'));
}

std::string ReadableHelpFormatter::make_option_opts(const CLI::Option* option) const {
  std::string text = CLI::Formatter::make_option_opts(option);
  const std::string shown = " " + option->get_type_name();
  if (option->get_option_text().empty() && text.rfind(shown, 0) == 0) {
    text.replace(0, shown.size(), " " + readable_type_name(option->get_type_name()));
  }
  return text;
}

}  // namespace rtiow
