#include "core/error.h"

#include <cstdio>

namespace rtiow {
namespace {

// Appends `text` escaped, stopping once `out` has grown by `max_chars`; true if all fitted.
bool append_printable(std::string& out, std::string_view text, std::size_t max_chars) {
  const std::size_t start = out.size();
  for (const char c : text) {
    if (out.size() - start >= max_chars) return false;
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\\') {
      out += "\\\\";
    } else if (byte < 0x20 || byte == 0x7f) {
      char escaped[5];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      out += escaped;
    } else {
      out += c;
    }
  }
  return true;
}

}  // namespace

std::string quote_value(std::string_view value, std::size_t max_chars) {
  std::string out = "'";
  if (!append_printable(out, value, max_chars)) out += "...";
  out += '\'';
  return out;
}

std::string one_line(std::string_view text, std::size_t max_chars) {
  std::string out;
  if (!append_printable(out, text, max_chars)) out += "...";
  return out;
}

}  // namespace rtiow
