#pragma once
// InvalidInput: the user asked for something the renderer refuses (a degenerate camera,
// a zero-sized image). The message names the setting and the problem, in one line.
//
// Any user value echoed in a message goes through quote_value(): control characters and
// newlines escaped, and cut to a sensible length, so the error stays one safe line even
// for a 50 MB key. one_line() is the last guard, applied by the CLI to every message.

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace rtiow {

class InvalidInput : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// `value` between single quotes, printable: bytes below 0x20 and 0x7f as \n, \t or \xNN,
// a backslash doubled; a value longer than `max_chars` keeps its head and tail around "...".
std::string quote_value(std::string_view value, std::size_t max_chars = 80);

// `text` made printable as quote_value() does (no quotes added) and cut to `max_chars`:
// long enough for a message that names a whole path the user must act on.
std::string one_line(std::string_view text, std::size_t max_chars = 8192);

// An error of the system (an errno value) in words; where it is a limit of this process or
// machine rather than a fault of the file (descriptors, memory, disk, processes), it says
// which: "Too many open files (this process may hold 8: ulimit -n)".
std::string system_error_text(int error);

// Whether `error` is a resource of the process or machine running out, not bad input.
bool is_exhausted_resource(int error);

// For quote_value() of a path the user must copy to act on (where a render is kept): whole,
// up to the system's path limit.
inline constexpr std::size_t kWholePath = 4096;

}  // namespace rtiow
