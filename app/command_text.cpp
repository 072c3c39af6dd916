#include "app/command_text.h"

#include <sys/ioctl.h>
#include <unistd.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <memory>
#include <regex>
#include <sstream>
#include <vector>

#include "core/limits/error.h"
#include "core/limits/nearest_name.h"

// --help (ReadableHelpFormatter) first, then the refusals of what could not be parsed.

namespace rtiow {

class ReadableHelpFormatter : public CLI::Formatter {
 public:
  std::string make_option(const CLI::Option* option, bool is_positional) const override;
  std::string make_option_opts(const CLI::Option* option) const override;
  std::string make_subcommand(const CLI::App* sub) const override;
  std::string make_description(const CLI::App* app) const override;
  std::string make_footer(const CLI::App* app) const override;
  std::string make_group(std::string group, bool is_positional,
                         std::vector<const CLI::Option*> options) const override;
};

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

std::shared_ptr<CLI::FormatterBase> readable_help_formatter() {
  return std::make_shared<ReadableHelpFormatter>();
}

}  // namespace rtiow

namespace rtiow {
namespace {

// The command the error belongs to: the deepest one parsed, or `app` itself.
const CLI::App& command_in_use(const CLI::App& app) {
  const std::vector<CLI::App*> parsed = app.get_subcommands();
  return parsed.empty() ? app : *parsed.back();
}

std::string full_name(const CLI::App& command) {
  return command.get_parent() == nullptr
             ? command.get_name()
             : full_name(*command.get_parent()) + " " + command.get_name();
}

// "--widht=3" is the option "--widht".
std::string option_part(const std::string& argument) {
  return argument.substr(0, argument.find('='));
}

std::string explain_extras(const CLI::App& command) {
  const std::string name = full_name(command);
  const std::vector<std::string> extras = command.remaining();
  if (extras.empty()) return "";
  const std::string& first = extras.front();
  std::string message;
  if (first.size() > 1 && first[0] == '-') {
    message = "unknown option " + quote_value(option_part(first)) + " for " + name;
    message += did_you_mean(option_part(first), option_spellings(command));
  } else {
    message = "unexpected argument " + quote_value(first) + " for " + name;
  }
  return message + " (see " + name + " --help)";
}

// What a CLI11 type name asks for, in words.
std::string kind_of(const std::string& type_name) {
  if (type_name.rfind("UINT", 0) == 0) return "a whole number of at least 0";
  if (type_name.rfind("INT", 0) == 0) return "a whole number";
  if (type_name.rfind("FLOAT", 0) == 0) return "a number";
  return "a value of type " + type_name;
}

// "Could not convert: --spp = ten": the option's kind, and the value given.
std::string explain_conversion(const CLI::App& command, const std::string& what) {
  static const std::regex pattern("Could not convert: (.*) = (.*)");
  std::smatch match;
  if (!std::regex_match(what, match, pattern)) return "";
  const std::string option_name = match[1], value = match[2];
  std::string kind = "another kind of value", type;
  for (const CLI::Option* option : command.get_options()) {
    if (option->check_name(option_name)) {
      type = option->get_type_name();
      kind = kind_of(type);
    }
  }
  // A whole number that still did not convert lies beyond the option's range: say the range.
  static const std::regex whole("-?[0-9]+");
  if (std::regex_match(value, whole) && (type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0)) {
    const bool below = value[0] == '-';
    const std::string bound = below                        ? std::to_string(INT_MIN)
                              : type.rfind("UINT", 0) == 0 ? "18446744073709551615 (2^64-1)"
                                                           : std::to_string(INT_MAX);
    return option_name + ": " + quote_value(value) + " is " +
           (below ? "below the smallest" : "beyond the largest") + " value it takes, " + bound +
           " (see " + full_name(command) + " --help)";
  }
  return option_name + " expects " + kind + ", not " + quote_value(value) + " (see " +
         full_name(command) + " --help)";
}

// "--sampler: sobel not in {independent,sobol,padded-sobol}" (a value outside an option's
// choices): the choices in words and the one a slip meant.
std::string explain_choice(const CLI::App& command, const std::string& what) {
  static const std::regex pattern("(-[^:]*): (.*) not in \\{(.*)\\}");
  std::smatch match;
  if (!std::regex_match(what, match, pattern)) return "";
  const std::string option_name = match[1], value = match[2], listed = match[3];
  std::vector<std::string> choices;
  std::string known;
  for (std::size_t start = 0; start <= listed.size();) {
    const std::size_t comma = std::min(listed.find(',', start), listed.size());
    choices.push_back(listed.substr(start, comma - start));
    known += (known.empty() ? "" : ", ") + choices.back();
    start = comma + 1;
  }
  return option_name + ": " + quote_value(value) + " is not one of " + known +
         did_you_mean(value, choices) + " (see " + full_name(command) + " --help)";
}

// "--lookfrom: At least 3 required but received 2": how many values, and how to give them.
std::string explain_count(const CLI::App& command, const std::string& what) {
  static const std::regex pattern(
      "(-[^:]*): At (?:[Ll]east|[Mm]ost) ([0-9]+) required but "
      "received ([0-9]+)");
  std::smatch match;
  if (!std::regex_match(what, match, pattern)) return "";
  const std::string option_name = match[1], wanted = match[2], got = match[3];
  if (wanted == "1") {
    return option_name + " takes one value, got " + got + ": give it once (see " +
           full_name(command) + " --help)";
  }
  // Values that are not numbers (bench --compare A.json B.json): as the help names them.
  for (const CLI::Option* option : command.get_options()) {
    if (!option->check_name(option_name)) continue;
    const std::string type = option->get_type_name();
    if (type.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZ,") != std::string::npos) {
      return option_name + " takes " + wanted + " values (" + type + "), got " + got + " (see " +
             full_name(command) + " --help)";
    }
  }
  std::string example;
  for (int i = 1; i <= std::stoi(wanted) && i <= 4; ++i) {
    example += (i > 1 ? "," : "") + std::to_string(i);
  }
  return option_name + " takes " + wanted + " numbers, got " + got + " (as " + option_name + " " +
         example + ", with commas or spaces between; see " + full_name(command) + " --help)";
}

// "A subcommand is required": rtiow alone, or only its options. The commands, as --help lists them.
std::string explain_missing_command(const CLI::App& app) {
  std::string commands;
  for (const CLI::App* command : app.get_subcommands({})) {
    if (command->get_group().empty()) continue;  // hidden (bench-point)
    commands += (commands.empty() ? "" : ", ") + command->get_name();
  }
  return "no command given: rtiow COMMAND [OPTIONS], where COMMAND is one of " + commands +
         " (see rtiow --help)";
}

}  // namespace

std::vector<std::string> option_spellings(const CLI::App& command) {
  std::vector<std::string> names;
  for (const CLI::Option* option : command.get_options()) {
    for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
    for (const std::string& name : option->get_snames()) names.push_back("-" + name);
  }
  return names;
}

std::string explain_parse_error(const CLI::App& app, const CLI::ParseError& error) {
  const CLI::App& command = command_in_use(app);
  std::string message;
  if (dynamic_cast<const CLI::ExtrasError*>(&error) != nullptr) message = explain_extras(command);
  if (dynamic_cast<const CLI::ConversionError*>(&error) != nullptr)
    message = explain_conversion(command, error.what());
  if (dynamic_cast<const CLI::ValidationError*>(&error) != nullptr)
    message = explain_choice(command, error.what());
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&error) != nullptr)
    message = explain_count(command, error.what());
  if (dynamic_cast<const CLI::RequiredError*>(&error) != nullptr && &command == &app &&
      app.get_subcommands().empty() && app.get_require_subcommand_min() > 0)
    message = explain_missing_command(app);
  if (!message.empty()) return message;
  return std::string(error.what()) + " (see " + full_name(command) + " --help)";
}

}  // namespace rtiow
