#include "core/scene_file/json_float.h"

#include <charconv>
#include <cmath>
#include <cstring>

namespace rtiow {
namespace {

// nlohmann's layout of a double with decimal digits `digits` (no leading zero) and the
// decimal point `point` places after the first digit's left edge: plain between 1e-5 and
// 1e15, otherwise "d.ddde+XX" with at least two exponent digits.
void append_laid_out(std::string& out, std::string_view digits, int point) {
  constexpr int kMinPoint = -4, kMaxPoint = 15;  // nlohmann: -4 and digits10 of double
  const int count = int(digits.size());
  if (count <= point && point <= kMaxPoint) {  // digits[000].0
    out.append(digits).append(std::size_t(point - count), '0').append(".0");
  } else if (0 < point && point <= kMaxPoint) {  // dig.its
    out.append(digits.substr(0, std::size_t(point)))
        .append(".")
        .append(digits.substr(std::size_t(point)));
  } else if (kMinPoint < point && point <= 0) {  // 0.[000]digits
    out.append("0.").append(std::size_t(-point), '0').append(digits);
  } else {  // d.igitse+XX
    out.append(digits.substr(0, 1));
    if (count > 1) out.append(".").append(digits.substr(1));
    int exponent = point - 1;
    out.append(exponent < 0 ? "e-" : "e+");
    exponent = std::abs(exponent);
    if (exponent < 10) out.push_back('0');
    char text[8];
    const auto end = std::to_chars(text, text + sizeof text, exponent).ptr;
    out.append(text, end);
  }
}

}  // namespace

void append_json_float(std::string& out, float value) {
  if (!std::isfinite(value)) {
    out.append("null");  // as nlohmann writes what JSON cannot hold
    return;
  }
  if (std::signbit(value)) out.push_back('-');
  value = std::fabs(value);
  if (value == 0) {
    out.append("0.0");
    return;
  }
  // The float's shortest text (fixed or scientific, whichever is shorter, as std::to_chars
  // chooses). A reader takes it as the double nearest to it, then the float nearest to that,
  // which in rare cases is not the float it came from (two roundings); then the double's own
  // shortest text is written instead. nlohmann then lays out that double's digits.
  char text[64];
  auto written = std::to_chars(text, text + sizeof text, value);
  double as_read = 0;
  std::from_chars(text, written.ptr, as_read);
  if (float(as_read) != value) written = std::to_chars(text, text + sizeof text, double(value));
  // Its significant digits, and where the decimal point falls after the first of them.
  char digits[64];
  int count = 0, point = 0, exponent = 0;
  bool after_point = false;
  const char* c = text;
  for (; c != written.ptr && *c != 'e'; ++c) {
    if (*c == '.') {
      after_point = true;
    } else if (count == 0 && *c == '0') {  // a leading zero
      if (after_point) --point;
    } else {
      digits[count++] = *c;
      if (!after_point) ++point;
    }
  }
  if (c != written.ptr) {
    ++c;
    if (*c == '+') ++c;
    std::from_chars(c, written.ptr, exponent);
  }
  while (count > 1 && digits[count - 1] == '0') --count;  // trailing zeros of a whole number
  append_laid_out(out, std::string_view(digits, std::size_t(count)), point + exponent);
}

}  // namespace rtiow
