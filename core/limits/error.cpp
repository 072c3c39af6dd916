#include "core/limits/error.h"

#include <sys/resource.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

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
  // A long value keeps its head and tail (a path keeps its file name and extension) around
  // "...": each part escaped on its own and cut to half the room.
  std::string out = "'";
  if (value.size() <= max_chars) {
    if (!append_printable(out, value, 4 * max_chars)) out += "...";
  } else {
    const std::size_t half = std::max<std::size_t>(max_chars / 2, 1);
    std::string head, tail;
    append_printable(head, value.substr(0, half), half);
    append_printable(tail, value.substr(value.size() - half), 4 * half);
    if (tail.size() > half) tail.erase(0, tail.size() - half);
    out += head + "..." + tail;
  }
  out += '\'';
  return out;
}

std::string one_line(std::string_view text, std::size_t max_chars) {
  std::string out;
  if (!append_printable(out, text, max_chars)) out += "...";
  return out;
}

bool is_exhausted_resource(int error) {
  return error == EMFILE || error == ENFILE || error == ENOMEM || error == ENOSPC ||
         error == EDQUOT || error == EAGAIN || error == EFBIG;
}

std::string system_error_text(int error) {
  std::string text = std::strerror(error);
  if (error == EMFILE) {
    struct rlimit limit {};
    if (::getrlimit(RLIMIT_NOFILE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
      text += " (this process may hold " + std::to_string(limit.rlim_cur) + ": ulimit -n)";
    }
  } else if (error == EFBIG) {
    text += " (a limit on the size of files this process writes: ulimit -f)";
  } else if (error == ENOMEM || error == EAGAIN) {
    text += " (a limit of this process or machine: memory, ulimit -v, or processes)";
  }
  return text;
}

}  // namespace rtiow
