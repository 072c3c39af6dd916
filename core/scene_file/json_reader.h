#pragma once
// Reading a scene file's JSON: a place in the document (a JSON pointer, spelt out only when an
// error names it) and a reader whose every accessor knows where it is and says so, in one
// line, when it refuses. Internal to the scene reader (it needs RapidJSON, which the installed
// package does not ask for).

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <initializer_list>
#include <limits>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/geometry/vec3.h"
#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/limits/nearest_name.h"
#include "core/scene_file/json_stream.h"

namespace rtiow::scene_json {

// A key as a JSON-pointer token, cut so that an error line stays short.
inline std::string escape_pointer_token(std::string_view key) {
  constexpr std::size_t kMaxShown = 40;
  std::string out;
  for (char c : key.substr(0, kMaxShown)) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  if (key.size() > kMaxShown) out += "...";
  return one_line(out, 4 * kMaxShown);  // NUL and control characters escaped
}

// A place in the document, spelt out as a JSON pointer only when an error names it (a
// million spheres must not build a million strings). Refers to its parent: pass it down,
// never keep it.
class Place {
 public:
  Place() = default;  // the root
  Place(const Place& parent, std::string_view key) : parent_(&parent), key_(key) {}
  Place(const Place& parent, std::size_t index)
      : parent_(&parent), index_(index), is_index_(true) {}

  std::string pointer() const {
    if (!parent_) return "";
    return parent_->pointer() + "/" +
           (is_index_ ? std::to_string(index_) : escape_pointer_token(key_));
  }

 private:
  const Place* parent_ = nullptr;
  std::string_view key_;
  std::size_t index_ = 0;
  bool is_index_ = false;
};

// Reading: every accessor knows where it is and says so when it refuses.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  const std::string& source() const { return source_; }

  [[noreturn]] void fail(const Place& at, const std::string& what) const {
    const std::string pointer = at.pointer();
    throw InvalidInput(source_ + ": " + (pointer.empty() ? "/" : pointer) + ": " + what);
  }

  const JsonValue& object(const JsonValue& v, const Place& at) const {
    if (!v.IsObject()) fail(at, "must be an object, got " + describe(v));
    return v;
  }

  // Refuses keys outside `allowed`: a misspelt field must not be ignored silently.
  void only(const JsonValue& obj, const Place& at,
            std::initializer_list<std::string_view> allowed) const {
    only(obj, at, std::span<const std::string_view>(allowed.begin(), allowed.size()));
  }
  void only(const JsonValue& obj, const Place& at,
            std::span<const std::string_view> allowed) const {
    for (const JsonMember& m : members(obj)) {
      const std::string_view key = text_of(m.name);
      if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
      std::string list;
      std::vector<std::string> names;
      for (std::string_view a : allowed) {
        list.append(list.empty() ? "" : ", ").append(a);
        names.emplace_back(a);
      }
      // A slip ("centre", "albedoo") is named with what it meant.
      fail(Place(at, key),
           "unknown field" + did_you_mean(key, names) + " (expected one of: " + list + ")");
    }
  }

  const JsonValue* find(const JsonValue& obj, const char* key) const {
    return find_member(obj, key);
  }

  const JsonValue& require(const JsonValue& obj, const Place& at, const char* key) const {
    const JsonValue* v = find(obj, key);
    if (!v) fail(at, std::string("missing field \"") + key + "\"");
    return *v;
  }

  double number(const JsonValue& v, const Place& at) const {
    if (!v.IsNumber()) fail(at, "must be a number, got " + describe(v));
    return v.GetDouble();  // finite: the parser refuses overflow, JSON has no NaN
  }

  // A float-valued field: finite also after rounding to float.
  float single(const JsonValue& v, const Place& at) const {
    const double d = number(v, at);
    if (std::abs(d) > double(std::numeric_limits<float>::max())) {
      fail(at, "is too large for single precision");
    }
    return float(d);
  }

  int integer(const JsonValue& v, const Place& at, int lo, int hi) const {
    // JSON has one number type: 1e3 is a whole number, and 1e20 one out of range.
    if (v.IsDouble()) {
      const double d = v.GetDouble();
      if (!std::isfinite(d) || std::floor(d) != d) {
        fail(at, "must be a whole number, got " + describe(v));
      }
      if (d < double(lo) || d > double(hi)) {
        fail(at, "must be from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " +
                     describe(v));
      }
      return int(d);
    }
    if (!v.IsNumber()) fail(at, "must be a whole number, got " + describe(v));
    // An unsigned value beyond int64 would wrap to a negative one: compare it unconverted.
    const bool in_range = v.IsUint64() ? v.GetUint64() <= std::uint64_t(std::max(hi, 0)) &&
                                             std::int64_t(v.GetUint64()) >= lo
                                       : v.GetInt64() >= lo && v.GetInt64() <= hi;
    if (!in_range) {
      fail(at, "must be from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " +
                   describe(v));
    }
    return int(v.GetInt64());
  }

  // A coordinate or length: within the range float rays and Embree trace.
  double bounded(const JsonValue& v, const Place& at) const {
    const double d = number(v, at);
    if (std::abs(d) > limits::kMaxCoordinate) {
      fail(at, "is beyond the limit of +-" + format(limits::kMaxCoordinate) +
                   " (the range rtiow traces), got " + format(d));
    }
    return d;
  }

  // A position or direction: three bounded numbers.
  Vec3d vec3(const JsonValue& v, const Place& at) const {
    if (!v.IsArray() || v.Size() != 3) fail(at, "must be an array of 3 numbers");
    return {bounded(v[0], Place(at, 0)), bounded(v[1], Place(at, 1)), bounded(v[2], Place(at, 2))};
  }

  // Three numbers, as a colour; whether they are in range is the caller's rule.
  Color numbers3(const JsonValue& v, const Place& at) const {
    if (!v.IsArray() || v.Size() != 3) fail(at, "must be an array of 3 numbers");
    return Color(
        Vec3d{number(v[0], Place(at, 0)), number(v[1], Place(at, 1)), number(v[2], Place(at, 2))});
  }

  // A sky colour: components in [0, 1].
  Color color(const JsonValue& v, const Place& at) const {
    const Color c = numbers3(v, at);
    for (rapidjson::SizeType i = 0; i < 3; ++i) {
      const double x = v[i].GetDouble();
      if (x < 0.0 || x > 1.0) fail(Place(at, i), "must be in [0, 1], got " + format(x));
    }
    return c;
  }

  std::string_view string(const JsonValue& v, const Place& at, const char* expected) const {
    if (!v.IsString()) fail(at, std::string("must be ") + expected + ", got " + describe(v));
    return text_of(v);
  }

  static std::string format(double d) {
    std::ostringstream s;
    s << d;
    return s.str();
  }

  // A short, safe description of a value: never the dump of a whole container.
  static std::string describe(const JsonValue& v) {
    if (v.IsObject()) return "an object of " + std::to_string(v.MemberCount()) + " members";
    if (v.IsArray()) return "an array of " + std::to_string(v.Size()) + " values";
    if (v.IsString()) return "string " + quote_value(text_of(v), 40);
    if (v.IsBool()) return v.GetBool() ? "boolean true" : "boolean false";
    if (v.IsNull()) return "null";
    if (v.IsUint64()) return "number " + std::to_string(v.GetUint64());
    if (v.IsInt64()) return "number " + std::to_string(v.GetInt64());
    char buffer[32];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, v.GetDouble()).ptr;
    return "number " + std::string(buffer, end);
  }

 private:
  std::string source_;
};

// A float as the shortest decimal that reads back (through double, as JSON does) to it.
inline double shortest(float f) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, f);
  const double d = std::strtod(std::string(buffer, result.ptr).c_str(), nullptr);
  return float(d) == f ? d : double(f);
}

}  // namespace rtiow::scene_json
