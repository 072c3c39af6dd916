#include "core/io/json_writer.h"

#include <nlohmann/json.hpp>

#include <stdexcept>
#include <variant>

namespace rtiow {

std::string json_quoted(std::string_view text) {
  // JSON holds only UTF-8: a byte that is not (a file name in another encoding) is written as
  // U+FFFD rather than ending the write in the library's exception.
  return nlohmann::json(std::string(text)).dump(-1, ' ', false,
                                                nlohmann::json::error_handler_t::replace);
}

std::string json_number(double value) {
  return nlohmann::json(value).dump();
}

// Before an array's element or an object's key: the comma after the one before, and the new
// line and indentation of the indented layout.
void JsonWriter::next_element() {
  if (open_.empty()) return;
  Open& level = open_.back();
  if (!level.empty) text_ += ',';
  level.empty = false;
  if (indent_ >= 0) {
    text_ += '\n';
    text_.append(std::size_t(indent_) * open_.size(), ' ');
  }
}

void JsonWriter::before_value() {
  if (!open_.empty() && open_.back().object && !after_key_)
    throw std::logic_error("JsonWriter: an object's value without its key");
  if (after_key_) {
    after_key_ = false;
    return;
  }
  next_element();
}

JsonWriter& JsonWriter::begin_object() {
  before_value();
  text_ += '{';
  open_.push_back({true});
  return *this;
}

JsonWriter& JsonWriter::begin_array() {
  before_value();
  text_ += '[';
  open_.push_back({false});
  return *this;
}

JsonWriter& JsonWriter::end() {
  if (open_.empty() || after_key_) throw std::logic_error("JsonWriter: nothing to end");
  const Open level = open_.back();
  open_.pop_back();
  if (!level.empty && indent_ >= 0) {  // an empty one stays "{}" or "[]"
    text_ += '\n';
    text_.append(std::size_t(indent_) * open_.size(), ' ');
  }
  text_ += level.object ? '}' : ']';
  return *this;
}

JsonWriter& JsonWriter::key(std::string_view name) {
  if (open_.empty() || !open_.back().object || after_key_)
    throw std::logic_error("JsonWriter: a key outside an object");
  next_element();
  text_ += json_quoted(name);
  text_ += indent_ >= 0 ? ": " : ":";
  after_key_ = true;
  return *this;
}

JsonWriter& JsonWriter::string(std::string_view text) {
  before_value();
  text_ += json_quoted(text);
  return *this;
}

JsonWriter& JsonWriter::number(double value) {
  before_value();
  text_ += json_number(value);
  return *this;
}

JsonWriter& JsonWriter::boolean(bool value) {
  before_value();
  text_ += value ? "true" : "false";
  return *this;
}

JsonWriter& JsonWriter::null() {
  before_value();
  text_ += "null";
  return *this;
}

JsonWriter& JsonWriter::whole_text(const std::string& digits) {
  before_value();
  text_ += digits;
  return *this;
}

JsonWriter& JsonWriter::value(const MetadataValue& value) {
  if (const auto* n = std::get_if<std::int64_t>(&value)) return whole(*n);
  if (const auto* d = std::get_if<double>(&value)) return number(*d);
  return string(std::get<std::string>(value));
}

JsonWriter& JsonWriter::members(const Metadata& entries) {
  for (const auto& [name, value] : entries) key(name).value(value);
  return *this;
}

}  // namespace rtiow
