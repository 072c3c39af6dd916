#include "core/scene_file/json_stream.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <unordered_set>
#include <vector>

#include "core/limits/error.h"
#include "core/limits/input_limits.h"

namespace rapidjson {
template <>
inline void SkipWhitespace(rtiow::JsonInput::Cursor& cursor) {
  cursor.skip_whitespace();
}
}  // namespace rapidjson

namespace rtiow {

JsonInput::JsonInput(Source source, std::uint64_t max_bytes, std::string name)
    : source_(std::move(source)), max_bytes_(max_bytes), name_(std::move(name)) {}

JsonInput::Cursor JsonInput::begin() {
  Cursor cursor(*this);
  refill(cursor);
  return cursor;
}

void JsonInput::refill(Cursor& cursor) {
  if (eof_) return;  // the cursor rests on the final sentinel
  Buffer& old = buffers_[current_];
  Buffer& next = buffers_[1 - current_];
  if (old.valid) {
    const char* begin = old.bytes.get();
    const char* end = begin + old.size;
    next.start_offset = old.start_offset + old.size;
    next.lines_before = old.lines_before + std::uint64_t(std::count(begin, end, '\n'));
    const auto newline =
        std::find(std::make_reverse_iterator(end), std::make_reverse_iterator(begin), '\n');
    next.line_start = newline.base() == begin
                          ? old.line_start
                          : old.start_offset + std::uint64_t(newline.base() - begin);
  }
  std::size_t size = 0;
  while (size < kBufferBytes) {
    const std::size_t n = source_(next.bytes.get() + size, kBufferBytes - size);
    if (n == 0) break;
    size += n;
  }
  delivered_ += size;
  if (delivered_ > max_bytes_) {
    throw InvalidInput(name_ + ": longer than the limit of " + std::to_string(max_bytes_ >> 20) +
                       " MiB");
  }
  next.size = size;
  next.valid = true;
  current_ = 1 - current_;
  cursor.begin_ = next.bytes.get();
  cursor.current_ = cursor.begin_;
  cursor.start_offset_ = next.start_offset;
  if (size < kBufferBytes) {
    // The end: a NUL sentinel after the last byte, where RapidJSON stops.
    next.bytes[size] = '\0';
    cursor.last_ = cursor.begin_ + size;
    eof_ = true;
  } else {
    cursor.last_ = cursor.begin_ + size - 1;
  }
}

bool JsonInput::at_end(const Cursor& cursor) const {
  return eof_ && cursor.current_ == cursor.last_ && cursor.begin_ == buffers_[current_].bytes.get();
}

const JsonInput::Buffer* JsonInput::buffer_at(std::uint64_t offset) const {
  for (const Buffer& b : buffers_) {
    if (b.valid && offset >= b.start_offset && offset <= b.start_offset + b.size) return &b;
  }
  return nullptr;
}

std::string JsonInput::position(std::uint64_t offset) const {
  const Buffer* b = buffer_at(offset);
  if (!b) {
    // Further back than what is still buffered (a token longer than a buffer).
    const Buffer& oldest =
        buffers_[0].valid && buffers_[1].valid
            ? (buffers_[0].start_offset < buffers_[1].start_offset ? buffers_[0] : buffers_[1])
            : buffers_[current_];
    return "line " + std::to_string(oldest.lines_before + 1);
  }
  const char* begin = b->bytes.get();
  const char* at = begin + (offset - b->start_offset);
  const auto lines = std::uint64_t(std::count(begin, at, '\n'));
  const auto newline =
      std::find(std::make_reverse_iterator(at), std::make_reverse_iterator(begin), '\n');
  const std::uint64_t line_start = newline.base() == begin
                                       ? b->line_start
                                       : b->start_offset + std::uint64_t(newline.base() - begin);
  return "line " + std::to_string(b->lines_before + lines + 1) + ", column " +
         std::to_string(offset - line_start + 1);
}

std::string_view JsonInput::text_at(std::uint64_t offset, std::size_t max_bytes) const {
  const Buffer* b = buffer_at(offset);
  if (!b) return {};
  const std::size_t from = std::size_t(offset - b->start_offset);
  return {b->bytes.get() + from, std::min(max_bytes, b->size - from)};
}

namespace {

// What a RapidJSON parse error means, in words a user of a scene file understands. (A number
// too big for a double is reported with its text, in parse_json_stream.)
const char* describe_parse_error(rapidjson::ParseErrorCode code) {
  switch (code) {
    case rapidjson::kParseErrorDocumentEmpty:
      return "unexpected end of input: there is no JSON value";
    case rapidjson::kParseErrorDocumentRootNotSingular:
      return "syntax error: expected end of input after the JSON value";
    case rapidjson::kParseErrorValueInvalid:
      return "syntax error: not a JSON value";
    case rapidjson::kParseErrorObjectMissName:
      return "syntax error: expected a key in double quotes";
    case rapidjson::kParseErrorObjectMissColon:
      return "syntax error: expected ':' after a key";
    case rapidjson::kParseErrorObjectMissCommaOrCurlyBracket:
      return "syntax error: expected ',' or '}' after a member";
    case rapidjson::kParseErrorArrayMissCommaOrSquareBracket:
      return "syntax error: expected ',' or ']' after a value";
    case rapidjson::kParseErrorStringUnicodeEscapeInvalidHex:
      return "syntax error: \\u must be followed by four hex digits";
    case rapidjson::kParseErrorStringUnicodeSurrogateInvalid:
      return "syntax error: invalid UTF-16 surrogate pair in a \\u escape";
    case rapidjson::kParseErrorStringEscapeInvalid:
      return "syntax error: invalid escape or unescaped control character in a string";
    case rapidjson::kParseErrorStringMissQuotationMark:
      return "syntax error: missing closing quote of a string";
    case rapidjson::kParseErrorStringInvalidEncoding:
      return "syntax error: invalid UTF-8 in a string";
    case rapidjson::kParseErrorNumberMissFraction:
      return "syntax error: a number needs digits after '.'";
    case rapidjson::kParseErrorNumberMissExponent:
      return "syntax error: a number needs digits in its exponent";
    default:
      return "syntax error";
  }
}

bool is_number_char(char c) {
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == 'e' || c == 'E';
}

}  // namespace

std::optional<JsonValue> read_json_number(std::string_view text, std::string& error) {
  const char* first = text.data();
  const char* last = first + text.size();
  const bool whole = std::none_of(text.begin(), text.end(),
                                  [](char c) { return c == '.' || c == 'e' || c == 'E'; });
  if (whole) {
    // A whole number: exact as an integer if it fits 64 bits, else a double (as JSON does).
    if (text.front() == '-') {
      std::int64_t i = 0;
      if (const auto r = std::from_chars(first, last, i); r.ec == std::errc() && r.ptr == last) {
        return JsonValue(i);
      }
    } else {
      std::uint64_t u = 0;
      if (const auto r = std::from_chars(first, last, u); r.ec == std::errc() && r.ptr == last) {
        return JsonValue(u);
      }
    }
  }
  double d = 0.0;
  const auto r = std::from_chars(first, last, d);
  if (r.ec == std::errc::result_out_of_range) {
    // Too large is an error; too small rounds to zero or a subnormal, as strtod does.
    d = std::strtod(std::string(text).c_str(), nullptr);
    if (!std::isfinite(d)) {
      error = "number overflow parsing " + quote_value(text, 40);
      return std::nullopt;
    }
  } else if (r.ec != std::errc() || r.ptr != last) {
    error = "cannot read the number " + quote_value(text, 40);
    return std::nullopt;
  }
  return JsonValue(d);
}

namespace {

// The SAX events of RapidJSON's reader, building small values. Handler failures are kept in
// `error` and reported by returning false, so that the reader says where it stopped.
class BoundedBuilder {
 public:
  BoundedBuilder(const std::map<std::string, StreamedMember, std::less<>>& streamed,
                 JsonDocument& root)
      : streamed_(streamed), root_(root), scratch_(scratch_buffer_, sizeof scratch_buffer_) {}

  const std::string& error() const { return error_; }

  bool Null() { return add(JsonValue()); }
  bool Bool(bool b) { return add(JsonValue(b)); }
  // Numbers come as text (kParseNumbersAsStringsFlag) and are read by std::from_chars.
  bool Int(int) { return unexpected(); }
  bool Uint(unsigned) { return unexpected(); }
  bool Int64(std::int64_t) { return unexpected(); }
  bool Uint64(std::uint64_t) { return unexpected(); }
  bool Double(double) { return unexpected(); }
  bool RawNumber(const char* text, rapidjson::SizeType length, bool) {
    return add_number(std::string_view(text, length));
  }
  bool String(const char* text, rapidjson::SizeType length, bool) {
    if (!check_length(length, "a string")) return false;
    return add(JsonValue(text, length, allocator()));
  }

  bool StartObject() { return open(rapidjson::kObjectType); }
  bool StartArray() { return open(rapidjson::kArrayType); }
  bool EndObject(rapidjson::SizeType) { return close(); }
  bool EndArray(rapidjson::SizeType) { return close(); }

  bool Key(const char* text, rapidjson::SizeType length, bool) {
    if (!check_length(length, "a key")) return false;
    const std::string_view key(text, length);
    Level& level = stack_.back();
    if (is_streamed_container()) {
      member_key_.assign(key);  // the callback refuses duplicates among dropped members
      return true;
    }
    if (level.has_key(key)) {
      return fail("the key " + quote_value(key, 40) + " appears twice in one object");
    }
    level.remember(key);
    pending_key_.SetString(text, length, allocator());
    return true;
  }

 private:
  // An open container; big objects also keep a set of their keys, so that the duplicate
  // check stays linear for a hostile object of a million members.
  struct Level {
    JsonValue* value;
    std::unique_ptr<std::unordered_set<std::string>> keys;

    bool has_key(std::string_view key) const {
      if (keys) return keys->count(std::string(key)) != 0;
      return find_member(*value, key) != nullptr;
    }
    void remember(std::string_view key) {
      constexpr rapidjson::SizeType kLinearScanMembers = 32;
      if (!keys && value->MemberCount() >= kLinearScanMembers) {
        keys = std::make_unique<std::unordered_set<std::string>>();
        for (const JsonMember& m : members(*value)) keys->emplace(text_of(m.name));
      }
      if (keys) keys->emplace(key);
    }
  };

  bool fail(std::string what) {
    error_ = std::move(what);
    return false;
  }

  bool unexpected() { return fail("internal error: a number not read as text"); }

  bool check_length(rapidjson::SizeType length, const char* kind) {
    if (length <= limits::kMaxJsonStringBytes) return true;
    return fail(std::string(kind) + " of " + std::to_string(length) +
                " bytes is longer than the limit of " +
                std::to_string(limits::kMaxJsonStringBytes));
  }

  bool add_number(std::string_view text) {
    std::optional<JsonValue> value = read_json_number(text, error_);
    return value && add(std::move(*value));
  }

  bool is_streamed_container() const { return stream_ && stack_.size() == kStreamLevel; }

  // Values inside a streamed member live in the scratch pool, the rest in the document's.
  rapidjson::MemoryPoolAllocator<>& allocator() {
    return stream_ && stack_.size() >= kStreamLevel ? scratch_ : root_.GetAllocator();
  }

  // Places a complete value: hands it over if it is a streamed member, else stores it.
  bool add(JsonValue&& value) {
    if (stack_.empty()) {
      JsonValue& root = root_;
      root = value;  // moves
      return true;
    }
    if (is_streamed_container()) {
      deliver(value);
      return true;
    }
    JsonValue& parent = *stack_.back().value;
    if (parent.IsArray()) {
      parent.PushBack(value, allocator());
    } else {
      parent.AddMember(pending_key_, value, allocator());
    }
    return true;
  }

  void deliver(const JsonValue& value) {
    stream_->on_member(member_key_, streamed_count_++, value);
    element_.SetNull();
    scratch_.Clear();
  }

  bool open(rapidjson::Type type) {
    if (int(stack_.size()) >= limits::kMaxJsonDepth) {
      return fail("nested deeper than the limit of " + std::to_string(limits::kMaxJsonDepth) +
                  " levels");
    }
    if (stack_.empty()) {
      if (type == rapidjson::kObjectType) {
        root_.SetObject();
      } else {
        root_.SetArray();
      }
      stack_.push_back({&root_, nullptr});
      return true;
    }
    if (is_streamed_container()) {
      element_ = JsonValue(type);  // a streamed member: built in the scratch pool
      stack_.push_back({&element_, nullptr});
      return true;
    }
    JsonValue& parent = *stack_.back().value;
    const bool root_member = stack_.size() == 1 && parent.IsObject();
    if (parent.IsArray()) {
      parent.PushBack(JsonValue(type), allocator());
      stack_.push_back({&parent[parent.Size() - 1], nullptr});
    } else {
      const std::string_view key(pending_key_.GetString(), pending_key_.GetStringLength());
      const auto it = root_member ? streamed_.find(key) : streamed_.end();
      parent.AddMember(pending_key_, JsonValue(type), allocator());
      stack_.push_back({&(parent.MemberBegin() + (parent.MemberCount() - 1))->value, nullptr});
      if (it != streamed_.end() && it->second.is_object == (type == rapidjson::kObjectType)) {
        // One of the chosen containers: it stays empty, its members go to the callback.
        stream_ = &it->second;
        streamed_count_ = 0;
      }
    }
    return true;
  }

  bool close() {
    stack_.pop_back();
    if (stream_ && stack_.size() + 1 == kStreamLevel) {
      stream_ = nullptr;  // the streamed container itself is complete
    } else if (is_streamed_container()) {
      deliver(element_);
    }
    return true;
  }

  const std::map<std::string, StreamedMember, std::less<>>& streamed_;
  // The stack depth of a streamed container's members' parent (the root, then the container).
  static constexpr std::size_t kStreamLevel = 2;
  JsonDocument& root_;
  char scratch_buffer_[1 << 14];
  rapidjson::MemoryPoolAllocator<> scratch_;
  JsonValue element_, pending_key_;
  std::vector<Level> stack_;
  std::string member_key_, error_;
  const StreamedMember* stream_ = nullptr;
  std::size_t streamed_count_ = 0;
};

}  // namespace

namespace {

// Parses `input` with `builder`; throws InvalidInput at the first error.
void parse_with(JsonInput& input, const std::string& source,
                const std::unique_ptr<BoundedBuilder>& builder) {
  constexpr unsigned kFlags =
      rapidjson::kParseValidateEncodingFlag | rapidjson::kParseNumbersAsStringsFlag;
  JsonInput::Cursor cursor = input.begin();
  rapidjson::Reader reader;
  const rapidjson::ParseResult result = reader.Parse<kFlags>(cursor, *builder);
  if (result.IsError()) {
    const std::uint64_t offset = result.Offset();
    std::string what;
    if (result.Code() == rapidjson::kParseErrorTermination) {
      what = builder->error();
    } else {
      what = describe_parse_error(result.Code());
      if (result.Code() == rapidjson::kParseErrorNumberTooBig) {
        std::string_view token = input.text_at(offset, 40);
        token = token.substr(
            0, std::size_t(std::find_if_not(token.begin(), token.end(), is_number_char) -
                           token.begin()));
        what = "number overflow parsing " + quote_value(token, 40);
      }
    }
    throw InvalidInput(source + ": " + input.position(offset) + ": " + what);
  }
  if (!input.at_end(cursor)) {
    // RapidJSON stops at a NUL byte as at the end: anything after the value is an error.
    throw InvalidInput(source + ": " + input.position(cursor.Tell()) +
                       ": syntax error: expected end of input after the JSON value");
  }
}

}  // namespace

void parse_json_stream(JsonInput& input, const std::string& source,
                       const std::map<std::string, StreamedMember, std::less<>>& streamed,
                       JsonDocument& root) {
  parse_with(input, source, std::make_unique<BoundedBuilder>(streamed, root));
}

}  // namespace rtiow
