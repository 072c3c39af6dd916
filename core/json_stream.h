#pragma once
// Reading JSON that may be huge and may be hostile, as a stream. nlohmann-json's SAX parser
// drives a builder that
//   - refuses nesting deeper than limits::kMaxJsonDepth while parsing (no deep value is ever
//     built, so no recursive destructor or dump can overflow the stack),
//   - refuses a duplicate key in any object (no "last one wins"),
//   - refuses strings and keys longer than limits::kMaxJsonStringBytes,
//   - hands each member of chosen top-level containers (a scene's "materials" and "spheres")
//     to a callback as soon as it is complete, and then drops it: memory grows with what the
//     callbacks keep, not with the text.
// Errors are InvalidInput "<source>: line L: <what>".

#include <cstdint>
#include <functional>
#include <istream>
#include <map>
#include <nlohmann/json.hpp>
#include <streambuf>
#include <string>

namespace rtiow {

// A stream buffer over a byte source that counts lines (for error positions) and refuses to
// deliver more than `max_bytes`.
class CountingInput : public std::streambuf {
 public:
  // Fills the buffer and returns the bytes written, 0 at the end; throws on a read error.
  using Source = std::function<std::size_t(char* buffer, std::size_t size)>;

  CountingInput(Source source, std::uint64_t max_bytes, std::string name);

  // The 1-based line of the next byte to be read.
  std::uint64_t line() const;

 protected:
  int_type underflow() override;

 private:
  Source source_;
  std::uint64_t max_bytes_, delivered_ = 0, lines_before_buffer_ = 0;
  std::string name_;
  char buffer_[1 << 16];
};

// One streamed top-level member: "key": {...} (an object) or "key": [...] (an array). The
// callback gets each member's key (objects) or index (arrays) and its value. For objects it
// must refuse duplicate keys itself: dropped members cannot be compared.
struct StreamedMember {
  bool is_object = false;
  std::function<void(const std::string& key, std::size_t index, const nlohmann::json& value)>
      on_member;
};

// Parses one JSON document from `in` (whose buffer is `input`). A streamed member of the root
// object stays in the result as an empty container.
nlohmann::json parse_json_stream(CountingInput& input, const std::string& source,
                                 const std::map<std::string, StreamedMember>& streamed);

}  // namespace rtiow
