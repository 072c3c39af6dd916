#pragma once
// A float as JSON text: the shortest decimal that reads back to the same float through a
// double (as JSON readers read numbers), laid out as nlohmann::json lays out a double
// ("1.0", "0.5", "1e-05", "1.5e+20"), so scene files look as they always have. Written
// directly into the caller's string: a million-sphere scene writes millions of them, and
// through a JSON value each cost an allocation and a strtod.

#include <string>

namespace rtiow {

void append_json_float(std::string& out, float value);

inline std::string json_float_text(float value) {
  std::string text;
  append_json_float(text, value);
  return text;
}

}  // namespace rtiow
