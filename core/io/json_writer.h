#pragma once
// JSON text written a value at a time, laid out as nlohmann-json lays out a document (dump() on
// one line, dump(indent) indented), with its strings and numbers formatted by nlohmann-json
// itself: the summaries, an image's description and a scene file's settings, without a
// document built first. The one place outside the measurements' figures
// (core/measure/figures.h) that compiles nlohmann-json; every JSON rtiow reads goes through
// core/scene_file/json_stream.h instead.

#include <concepts>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/image_output.h"

namespace rtiow {

class JsonWriter {
 public:
  // `indent` < 0: one line, as dump(); else as dump(indent).
  explicit JsonWriter(int indent = -1) : indent_(indent) {}

  JsonWriter& begin_object();
  JsonWriter& begin_array();
  JsonWriter& end();  // the innermost object or array
  // An object's member: its key, then its value.
  JsonWriter& key(std::string_view name);

  JsonWriter& string(std::string_view text);
  JsonWriter& number(double value);  // NaN and infinities as null, as nlohmann-json writes them
  JsonWriter& boolean(bool value);
  JsonWriter& null();
  template <std::integral T>
  JsonWriter& whole(T value) {
    if constexpr (std::is_signed_v<T>) return whole_text(std::to_string(std::int64_t(value)));
    return whole_text(std::to_string(std::uint64_t(value)));
  }
  JsonWriter& value(const MetadataValue& value);  // a whole number, a number or a string
  // Each entry as a member, in order.
  JsonWriter& members(const Metadata& entries);

  // The text so far: a whole document once every object and array is ended.
  const std::string& text() const { return text_; }

 private:
  struct Open {
    bool object;
    bool empty = true;
  };
  void before_value();
  void next_element();
  JsonWriter& whole_text(const std::string& digits);

  int indent_;
  std::string text_;
  std::vector<Open> open_;
  bool after_key_ = false;
};

// `text` as a JSON string, quoted and escaped as nlohmann-json writes it; each byte that is not
// UTF-8 as U+FFFD, the replacement character (JSON holds nothing else).
std::string json_quoted(std::string_view text);

// `value` as nlohmann-json writes a double (13.0, 0.1, 1e-05; null where not finite).
std::string json_number(double value);

}  // namespace rtiow
