#pragma once
// Reading JSON that may be huge and may be hostile, as a stream. RapidJSON's SAX reader (the
// fastest well-kept JSON lexer Debian packages: 0.7 s for a 158 MB scene, against 2 s for
// nlohmann's) drives a builder that
//   - refuses nesting deeper than limits::kMaxJsonDepth while parsing (no deep value is ever
//     built, so no recursive destructor can overflow the stack),
//   - refuses a duplicate key in any object (no "last one wins"),
//   - refuses strings and keys longer than limits::kMaxJsonStringBytes,
//   - reads numbers with std::from_chars (correctly rounded, as strtod),
//   - hands each member of chosen top-level containers (a scene's "materials" and "spheres")
//     to a callback as soon as it is complete, built in a scratch pool that is then reset:
//     memory grows with what the callbacks keep, not with the text.
// Errors are InvalidInput "<source>: line L, column C: <what>".

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "core/scene_file/json_whitespace.h"
#include "core/scene_file/rapidjson.h"

namespace rtiow {

// A byte source as a RapidJSON input stream: buffered, refusing more than `max_bytes`, and
// able to say where (line, column) a byte offset of the recent input lies.
class JsonInput {
 public:
  // Fills the buffer and returns the bytes written, 0 at the end; throws on a read error.
  using Source = std::function<std::size_t(char* buffer, std::size_t size)>;

  JsonInput(Source source, std::uint64_t max_bytes, std::string name);
  JsonInput(const JsonInput&) = delete;
  JsonInput& operator=(const JsonInput&) = delete;

  // A source that reads `text` (which must outlive it).
  static Source from_text(std::string_view text) {
    return [text, offset = std::size_t(0)](char* buffer, std::size_t size) mutable {
      const std::size_t n = std::min(size, text.size() - offset);
      std::memcpy(buffer, text.data() + offset, n);
      offset += n;
      return n;
    };
  }

  // "line L, column C" of a byte offset; "line L" alone if the offset is no longer buffered.
  std::string position(std::uint64_t offset) const;

  // Up to `max_bytes` of the input from `offset`, if still buffered (for error messages).
  std::string_view text_at(std::uint64_t offset, std::size_t max_bytes) const;

  // The RapidJSON stream: a small cursor that RapidJSON copies into registers while it
  // parses (StreamTraits::copyOptimization) and that refills through its input.
  class Cursor {
   public:
    using Ch = char;
    explicit Cursor(JsonInput& input) : input_(&input) {}
    Ch Peek() const { return *current_; }
    Ch Take() {
      const Ch c = *current_;
      if (current_ < last_) {
        ++current_;
      } else {
        input_->refill(*this);
      }
      return c;
    }
    // Skips JSON whitespace a buffer at a time (RapidJSON's own loop takes a byte at a time).
    void skip_whitespace() {
      for (;;) {
        while (current_ < last_ && is_json_space(*current_)) ++current_;
        if (current_ < last_ || !is_json_space(*current_)) return;
        Take();  // the buffer's last byte is a space: move to the next buffer
      }
    }
    std::size_t Tell() const {
      return std::size_t(start_offset_ + std::uint64_t(current_ - begin_));
    }
    // Writing is never used by a non-destructive parse but must exist.
    Ch* PutBegin() { return nullptr; }
    void Put(Ch) {}
    void Flush() {}
    std::size_t PutEnd(Ch*) { return 0; }

   private:
    friend class JsonInput;
    JsonInput* input_;
    const Ch* begin_ = nullptr;       // the buffer the cursor is in
    const Ch* current_ = nullptr;     // the next byte
    const Ch* last_ = nullptr;        // the buffer's last byte (a NUL sentinel at the end)
    std::uint64_t start_offset_ = 0;  // input offset of begin_
  };

  Cursor begin();

  // True if `cursor` stands after the last byte (a NUL byte inside the input is not the end).
  bool at_end(const Cursor& cursor) const;

 private:
  static constexpr std::size_t kBufferBytes = std::size_t(1) << 16;

  // Moves `cursor` to the next buffer (the current one is kept as the previous, so that
  // error positions and tokens just behind the cursor can still be shown).
  void refill(Cursor& cursor);

  struct Buffer {
    std::unique_ptr<char[]> bytes{new char[kBufferBytes + 1]};
    std::size_t size = 0;            // bytes of input held (the sentinel not counted)
    std::uint64_t start_offset = 0;  // input offset of bytes[0]
    std::uint64_t lines_before = 0;  // newlines in the input before bytes[0]
    std::uint64_t line_start = 0;    // input offset just after the last newline before it
    bool valid = false;
  };

  // The buffer holding `offset` (its end included), if still held.
  const Buffer* buffer_at(std::uint64_t offset) const;

  Source source_;
  std::uint64_t max_bytes_, delivered_ = 0;
  std::string name_;
  Buffer buffers_[2];
  int current_ = 0;
  bool eof_ = false;
};

// One streamed top-level member: "key": {...} (an object) or "key": [...] (an array). The
// callback gets each member's key (objects) or index (arrays) and its value, which lives
// until the callback returns. For objects it must refuse duplicate keys itself: members are
// dropped, so they cannot be compared.
struct StreamedMember {
  bool is_object = false;
  std::function<void(std::string_view key, std::size_t index, const JsonValue& value)> on_member;
};

// Parses one JSON document from `input` into `root` (whose allocator owns it). A streamed
// member of the root object stays in the result as an empty container.
void parse_json_stream(JsonInput& input, const std::string& source,
                       const std::map<std::string, StreamedMember, std::less<>>& streamed,
                       JsonDocument& root);

// The value a number's text reads as: a whole number that fits 64 bits as that integer, any
// other as the nearest double (std::from_chars; one too small for a double rounds to zero or
// a subnormal, as strtod does); nothing, and `error` set, for one too large or not a number.
std::optional<JsonValue> read_json_number(std::string_view text, std::string& error);

}  // namespace rtiow
