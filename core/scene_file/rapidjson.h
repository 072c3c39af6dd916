#pragma once
// RapidJSON, configured once for rtiow: every file that uses it includes this header.
// A failed RapidJSON assertion (a bug of ours, such as reading a string as a number) throws
// instead of aborting: no library assertion may end the process.

#include <span>
#include <stdexcept>
#include <string_view>

#ifndef RAPIDJSON_ASSERT
#define RAPIDJSON_ASSERT(condition) \
  ((condition) ? void(0) : throw std::logic_error("RapidJSON assertion failed: " #condition))
#endif

#include <rapidjson/document.h>
#include <rapidjson/reader.h>

namespace rtiow {

// Values built in a memory pool: no allocation per value, freed all at once.
using JsonValue = rapidjson::Value;
using JsonDocument = rapidjson::Document;
using JsonMember = JsonValue::Member;

// An object's members as a span: RapidJSON 1.1's iterator comparisons are ambiguous in C++20.
inline std::span<const JsonMember> members(const JsonValue& object) {
  if (object.MemberCount() == 0) return {};
  return {&*object.MemberBegin(), object.MemberCount()};
}

// A string value's bytes (which may hold NUL).
inline std::string_view text_of(const JsonValue& string) {
  return {string.GetString(), string.GetStringLength()};
}

// The member of `object` named `key`, or null (also where `object` is no object).
inline const JsonValue* find_member(const JsonValue& object, std::string_view key) {
  if (!object.IsObject()) return nullptr;
  for (const JsonMember& m : members(object)) {
    if (text_of(m.name) == key) return &m.value;
  }
  return nullptr;
}

}  // namespace rtiow
