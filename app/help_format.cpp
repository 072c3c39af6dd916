#include "app/help_format.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <cstdlib>
#include <sstream>
#include <vector>

namespace rtiow {
namespace {

std::vector<std::string> words_of(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

// `text`'s words in lines of at most `room` characters (a longer word has a line of its own),
// each line after the first starting with `indent`.
std::string fill(const std::string& text, std::size_t room, const std::string& indent) {
  std::string out, line;
  for (const std::string& word : words_of(text)) {
    if (!line.empty() && line.size() + 1 + word.size() > room) {
      out += line + "\n" + indent;
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  return out + line;
}

}  // namespace

std::string readable_type_name(const std::string& type_name) {
  const std::size_t choices = type_name.find(":{");
  if (choices != std::string::npos) {
    return type_name.substr(choices + 1, type_name.find('}', choices) - choices);
  }
  // CLI11's own names carry what a check added after a colon ("TEXT:FILE"); a name rtiow gave
  // (HOST:PORT) is shown whole.
  const std::size_t colon = type_name.find(':');
  const std::string before = type_name.substr(0, colon);
  for (const char* cli11 : {"TEXT", "INT", "UINT", "FLOAT", "BOOLEAN", "ENUM"}) {
    if (before == cli11) return before;
  }
  return type_name;
}

std::size_t help_width() {
  if (const char* columns = std::getenv("COLUMNS")) {
    char* end = nullptr;
    const long value = std::strtol(columns, &end, 10);
    if (end != columns && *end == '\0' && value >= 40 && value <= 1000) return std::size_t(value);
  }
  winsize size{};
  if (::isatty(STDOUT_FILENO) == 1 && ::ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0 &&
      size.ws_col >= 40) {
    return size.ws_col;
  }
  return 80;
}

std::string wrap_beside(const std::string& left, const std::string& text, std::size_t column,
                        std::size_t width) {
  const std::string indent(column, ' ');
  const std::size_t room = width > column + 20 ? width - column : 20;
  std::string out = "  " + left;
  if (text.empty()) return out + "\n";
  if (out.size() + 1 > column) {
    out += "\n" + indent;
  } else {
    out += std::string(column - out.size(), ' ');
  }
  return out + fill(text, room, indent) + "\n";
}

std::string ReadableHelpFormatter::make_option(const CLI::Option* option,
                                               bool is_positional) const {
  return wrap_beside(make_option_name(option, is_positional) + make_option_opts(option),
                     make_option_desc(option), get_column_width(), help_width());
}

std::string ReadableHelpFormatter::make_option_opts(const CLI::Option* option) const {
  std::string text = CLI::Formatter::make_option_opts(option);
  const std::string shown = " " + option->get_type_name();
  if (option->get_option_text().empty() && text.rfind(shown, 0) == 0) {
    const std::string readable = readable_type_name(option->get_type_name());
    text.replace(0, shown.size(), " " + readable);
    // A name that spells its values out (X,Y,Z) needs no " x 3" after it.
    const std::string count = " x " + std::to_string(option->get_expected_max());
    if (readable.find(',') != std::string::npos &&
        text.compare(1 + readable.size(), count.size(), count) == 0) {
      text.erase(1 + readable.size(), count.size());
    }
  }
  return text;
}

std::string ReadableHelpFormatter::make_subcommand(const CLI::App* sub) const {
  return wrap_beside(sub->get_display_name(true), sub->get_description(), get_column_width(),
                     help_width());
}

std::string ReadableHelpFormatter::make_description(const CLI::App* app) const {
  // CLI11's own lines about required options are not used by rtiow's commands.
  const std::string description = app->get_description();
  return description.empty() ? "" : fill(description, help_width(), "") + "\n";
}

std::string ReadableHelpFormatter::make_group(std::string group, bool is_positional,
                                              std::vector<const CLI::Option*> options) const {
  // CLI11 puts a blank line between groups itself; its own group adds one more before each.
  // The first group, after the usage line (the positionals, or else help's "Options"), keeps it.
  const bool first = group == "Positionals" || group == "Options";
  std::string out = (first ? "\n" : "") + group + ":\n";
  for (const CLI::Option* option : options) out += make_option(option, is_positional);
  return out;
}

std::string ReadableHelpFormatter::make_footer(const CLI::App* app) const {
  const std::string footer = app->get_footer();
  return footer.empty() ? "" : fill(footer, help_width(), "") + "\n";
}

}  // namespace rtiow
