#include "core/scene_file/run_records.h"

#include <charconv>
#include <string_view>

#include "core/limits/input_limits.h"
#include "core/scene_file/json_whitespace.h"
#include "core/scene_file/material_json.h"
#include "core/scene_file/name_index.h"
#include "core/scene_file/rapidjson.h"

namespace rtiow {
namespace {

// RapidJSON's events for one key or one member, into flat fields. Any event a scene member
// cannot have (a nested object, an array of other than three numbers, null, a boolean, a
// repeated field) stops the parse.
class MemberHandler : public rapidjson::BaseReaderHandler<rapidjson::UTF8<>, MemberHandler> {
 public:
  // The next parse reads a key of the materials object (a string).
  void expect_key() { state_ = kKey; }
  // The next parse reads a member (an object).
  void expect_member() {
    state_ = kMember;
    fields_.clear();
  }

  std::string_view key() const { return key_; }
  const MemberFields& fields() const { return fields_; }

  bool Default() { return false; }
  bool RawNumber(const char* text, rapidjson::SizeType length, bool) {
    const std::optional<double> value = read_number(std::string_view(text, length));
    if (!value) return false;
    if (state_ == kValue) {
      field_->kind = MemberField::kNumber;
      field_->numbers[0] = *value;
      state_ = kFieldKey;
      return true;
    }
    if (state_ != kTriple || numbers_ == 3) return false;
    field_->numbers[numbers_++] = *value;
    return true;
  }
  bool String(const char* text, rapidjson::SizeType length, bool) {
    if (length > limits::kMaxJsonStringBytes) return false;
    if (state_ == kKey) {
      key_ = std::string_view(text, length);
      state_ = kDone;
      return true;
    }
    if (state_ != kValue) return false;
    field_->kind = MemberField::kString;
    field_->text = std::string_view(text, length);
    state_ = kFieldKey;
    return true;
  }
  bool Key(const char* text, rapidjson::SizeType length, bool) {
    if (state_ != kFieldKey) return false;
    field_ = fields_.add(std::string_view(text, length));  // null if repeated
    state_ = kValue;
    return field_ != nullptr;
  }
  bool StartObject() {
    if (state_ != kMember) return false;
    state_ = kFieldKey;
    return true;
  }
  bool EndObject(rapidjson::SizeType) {
    if (state_ != kFieldKey) return false;
    state_ = kDone;
    return true;
  }
  bool StartArray() {
    if (state_ != kValue) return false;
    field_->kind = MemberField::kTriple;
    numbers_ = 0;
    state_ = kTriple;
    return true;
  }
  bool EndArray(rapidjson::SizeType) {
    if (state_ != kTriple || numbers_ != 3) return false;
    state_ = kFieldKey;
    return true;
  }

  bool done() const { return state_ == kDone; }

 private:
  // The double the one-piece reading makes of a number (read_json_number, then GetDouble),
  // read straight from its text: that reading's whole numbers, converted, are the correctly
  // rounded value too, except "-0", an integer zero there. What from_chars does not take
  // whole goes that reading's way.
  std::optional<double> read_number(std::string_view text) {
    double d = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), d);
    if (error == std::errc() && end == text.data() + text.size()) {
      if (d == 0.0 && text.find_first_of(".eE") == std::string_view::npos) return 0.0;
      return d;
    }
    const std::optional<JsonValue> value = read_json_number(text, error_);
    if (!value) return std::nullopt;
    return value->GetDouble();
  }

  enum State { kKey, kMember, kFieldKey, kValue, kTriple, kDone };
  State state_ = kDone;
  MemberFields fields_;
  MemberField* field_ = nullptr;
  std::size_t numbers_ = 0;
  std::string_view key_;  // in the text, as the fields' (member_fields.h)
  std::string error_;
};

}  // namespace

bool read_run_records(std::string& window, const MemberRun& run, RunRecords& records) {
  constexpr unsigned kFlags = rapidjson::kParseInsituFlag | rapidjson::kParseValidateEncodingFlag |
                              rapidjson::kParseNumbersAsStringsFlag |
                              rapidjson::kParseStopWhenDoneFlag;
  char* const begin = window.data() + (run.text.data() - window.data());
  // The window ends in a NUL: a parse that runs past the run (a member the scan cut wrongly)
  // stops there at the latest, and is refused below.
  const char* const end = begin + run.text.size();
  rapidjson::Reader reader;
  rapidjson::InsituStringStream in(begin);
  MemberHandler handler;
  const bool materials = run.key == "materials";
  const auto parse = [&] { return !reader.Parse<kFlags>(in, handler).IsError() && handler.done(); };
  const auto skip_space = [&] {
    while (in.src_ < end && is_json_space(*in.src_)) ++in.src_;
  };
  std::size_t members = 0;
  for (;;) {
    if (run.is_object) {
      handler.expect_key();
      if (!parse()) return false;
      skip_space();
      if (in.src_ >= end || *in.src_ != ':') return false;
      ++in.src_;
    }
    handler.expect_member();
    if (!parse()) return false;
    if (materials) {
      std::optional<Material> material = material_from_fields(handler.fields());
      if (!material) return false;
      records.materials.push_back({handler.key(), *material});
      records.hashes.push_back(NameIndex::hash(handler.key()));
    } else {
      std::optional<SphereRecord> sphere = sphere_from_fields(handler.fields());
      if (!sphere) return false;
      records.hashes.push_back(NameIndex::hash(sphere->material));
      records.spheres.push_back(std::move(*sphere));
    }
    ++members;
    skip_space();
    if (in.src_ == end) break;
    if (in.src_ > end || *in.src_ != ',') return false;
    ++in.src_;
  }
  return members == run.members;
}

}  // namespace rtiow
