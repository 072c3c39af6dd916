#pragma once
// A number as the shortest text that reads back to the same bits: what a user typed (0.05, not
// 0.0500000007), and exact in files and identities.

#include <charconv>
#include <string>

namespace rtiow {

template <typename T>
std::string shortest_text(T value) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
}

}  // namespace rtiow
