#pragma once
// JSON's whitespace (RFC 8259: space, tab, line feed, carriage return), the one definition the
// scanners share.

namespace rtiow {

template <typename Char>
constexpr bool is_json_space(Char c) {
  return c == ' ' || c == '\n' || c == '\r' || c == '\t';
}

}  // namespace rtiow
