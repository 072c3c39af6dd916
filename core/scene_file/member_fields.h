#pragma once
// A scene member's fields as the fast reading of a big file sees them (run_records.cpp): a
// flat object whose values are each a number, a string or three numbers, which is every shape
// a sphere or a material has. The fast reading builds no JSON values and says nothing when it
// refuses: whatever it cannot take, the one-piece reading takes or refuses by name.

#include <array>
#include <cstddef>
#include <string_view>

namespace rtiow {

// Its key and text lie in the text being read (RapidJSON decodes strings in place there), which
// outlives the fields: they are made into a sphere or a material before the next member.
struct MemberField {
  enum Kind { kNumber, kString, kTriple };
  std::string_view key;
  Kind kind = kNumber;
  std::array<double, 3> numbers{};  // kNumber: [0]; kTriple: all three
  std::string_view text;            // kString
};

class MemberFields {
 public:
  // More fields than any member has: a member with more is refused (the one-piece reading
  // says which field is unknown or repeated).
  static constexpr std::size_t kCapacity = 8;

  void clear() { count_ = 0; }
  std::size_t size() const { return count_; }

  // A new field named `key`; null when the member already has one of that name, or too many.
  MemberField* add(std::string_view key) {
    if (count_ == kCapacity || find(key)) return nullptr;
    MemberField& field = fields_[count_++];
    field.key = key;
    return &field;
  }

  const MemberField* find(std::string_view key) const {
    for (std::size_t i = 0; i < count_; ++i) {
      if (fields_[i].key == key) return &fields_[i];
    }
    return nullptr;
  }

  MemberField& back() { return fields_[count_ - 1]; }

 private:
  std::array<MemberField, kCapacity> fields_;
  std::size_t count_ = 0;
};

}  // namespace rtiow
