#include "core/json_stream.h"

#include <algorithm>
#include <vector>

#include "core/error.h"
#include "core/input_limits.h"

namespace rtiow {

using json = nlohmann::json;

CountingInput::CountingInput(Source source, std::uint64_t max_bytes, std::string name)
    : source_(std::move(source)), max_bytes_(max_bytes), name_(std::move(name)) {
  setg(buffer_, buffer_, buffer_);
}

std::uint64_t CountingInput::line() const {
  return lines_before_buffer_ + std::uint64_t(std::count(eback(), gptr(), '\n')) + 1;
}

CountingInput::int_type CountingInput::underflow() {
  lines_before_buffer_ += std::uint64_t(std::count(eback(), egptr(), '\n'));
  const std::size_t n = source_(buffer_, sizeof buffer_);
  setg(buffer_, buffer_, buffer_ + n);
  if (n == 0) return traits_type::eof();
  delivered_ += n;
  if (delivered_ > max_bytes_) {
    throw InvalidInput(name_ + ": longer than the limit of " + std::to_string(max_bytes_ >> 20) +
                       " MiB");
  }
  return traits_type::to_int_type(buffer_[0]);
}

namespace {

// The SAX events of nlohmann::json::sax_parse, building small DOM values.
class BoundedBuilder {
 public:
  BoundedBuilder(const CountingInput& input, const std::string& source,
                 const std::map<std::string, StreamedMember>& streamed)
      : input_(input), source_(source), streamed_(streamed) {}

  json take_root() { return std::move(root_); }

  bool null() { return add(json(nullptr)); }
  bool boolean(bool value) { return add(json(value)); }
  bool number_integer(json::number_integer_t value) { return add(json(value)); }
  bool number_unsigned(json::number_unsigned_t value) { return add(json(value)); }
  bool number_float(json::number_float_t value, const std::string&) { return add(json(value)); }
  bool string(std::string& value) {
    check_length(value, "a string");
    return add(json(std::move(value)));
  }
  bool binary(json::binary_t&) { fail("binary values are not JSON"); }

  bool start_object(std::size_t) { return open(json::object()); }
  bool start_array(std::size_t) { return open(json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(std::string& key) {
    check_length(key, "a key");
    json& object = *stack_.back();
    if (object.contains(key))
      fail("the key " + quote_value(key, 40) + " appears twice in one object");
    if (stack_.size() == 2) member_key_ = key;  // a member of a root member: maybe streamed
    key_ = std::move(key);
    return true;
  }

  bool parse_error(std::size_t, const std::string& last_token,
                   const nlohmann::detail::exception& e) {
    // nlohmann's text: "[json.exception.parse_error.101] parse error at line L, column C:
    // ...; last read: '<token>'". Keep the place and the reason, quote the token safely.
    std::string what = e.what();
    if (const auto bracket = what.find("] "); bracket != std::string::npos) {
      what = what.substr(bracket + 2);
    }
    if (const auto last = what.find("; last read:"); last != std::string::npos) {
      what = what.substr(0, last) + "; last read: " + quote_value(last_token, 40);
    }
    if (what.find(" line ") == std::string::npos && what.rfind("line ", 0) != 0) {
      fail(what);  // e.g. a number too large for a double: add the line ourselves
    }
    throw InvalidInput(source_ + ": " + what);
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InvalidInput(source_ + ": line " + std::to_string(input_.line()) + ": " + what);
  }

  void check_length(const std::string& text, const char* kind) const {
    if (text.size() > limits::kMaxJsonStringBytes) {
      fail(std::string(kind) + " of " + std::to_string(text.size()) +
           " bytes is longer than the limit of " + std::to_string(limits::kMaxJsonStringBytes));
    }
  }

  // Places a value in the container on top of the stack (or makes it the root); returns it.
  json& place(json&& value) {
    if (stack_.empty()) {
      root_ = std::move(value);
      return root_;
    }
    json& parent = *stack_.back();
    if (parent.is_array()) {
      parent.push_back(std::move(value));
      return parent.back();
    }
    return parent[key_] = std::move(value);
  }

  bool add(json&& value) {
    place(std::move(value));
    member_completed();
    return true;
  }

  bool open(json&& container) {
    if (int(stack_.size()) >= limits::kMaxJsonDepth) {
      fail("nested deeper than the limit of " + std::to_string(limits::kMaxJsonDepth) + " levels");
    }
    const bool is_object = container.is_object();
    if (stack_.size() == 1 && stack_.front()->is_object()) {
      // A member of the root object: stream it if it is one of the chosen containers.
      const auto it = streamed_.find(key_);
      stream_ = it != streamed_.end() && it->second.is_object == is_object ? &it->second : nullptr;
      streamed_count_ = 0;
    }
    stack_.push_back(&place(std::move(container)));
    return true;
  }

  bool close() {
    stack_.pop_back();
    member_completed();
    return true;
  }

  // After a value is complete: if it is a member of the streamed container, hand it over.
  void member_completed() {
    if (!stream_ || stack_.size() != 2) return;
    json& container = *stack_.back();
    if (container.is_array()) {
      stream_->on_member(std::string(), streamed_count_++, container.back());
      container.get_ref<json::array_t&>().pop_back();
    } else {
      const auto it = container.find(member_key_);
      stream_->on_member(member_key_, streamed_count_++, *it);
      container.erase(it);
    }
  }

  const CountingInput& input_;
  const std::string& source_;
  const std::map<std::string, StreamedMember>& streamed_;
  json root_;
  std::vector<json*> stack_;
  std::string key_, member_key_;
  const StreamedMember* stream_ = nullptr;
  std::size_t streamed_count_ = 0;
};

}  // namespace

json parse_json_stream(CountingInput& input, const std::string& source,
                       const std::map<std::string, StreamedMember>& streamed) {
  std::istream in(&input);
  BoundedBuilder builder(input, source, streamed);
  json::sax_parse(in, &builder);
  return builder.take_root();
}

}  // namespace rtiow
