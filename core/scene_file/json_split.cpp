#include "core/scene_file/json_split.h"

#include <algorithm>
#include <array>
#include <bit>
#include <mutex>
#include <utility>

#include "core/scene_file/json_byte_masks.h"
#include "core/scene_file/json_whitespace.h"

namespace rtiow {
namespace {

using ByteSet = std::array<bool, 256>;

constexpr ByteSet byte_set(std::string_view bytes) {
  ByteSet set{};
  for (const char c : bytes) set[static_cast<unsigned char>(c)] = true;
  return set;
}

// The bytes that end a stretch the scan skips: inside a string, and inside a split container.
constexpr ByteSet kStringStops = byte_set("\"\\");
constexpr ByteSet kContainerStops = byte_set("\"{}[],");

std::size_t skip_until(const char* data, std::size_t i, std::size_t to, const ByteSet& stops) {
  while (i < to && !stops[static_cast<unsigned char>(data[i])]) ++i;
  return i;
}

// The longest member or skeleton the scan takes (more when the window is longer).
constexpr std::size_t kMaxPieceBytes = std::size_t(1) << 20;

}  // namespace

// Windows' buffers are used again once every run in them is read: a fresh buffer of a few
// MiB costs its page faults each time, and that cost is on the one thread that cuts.
struct JsonSplitter::BufferPool {
  std::mutex mutex;
  std::vector<std::unique_ptr<std::string>> free;
};

std::shared_ptr<std::string> JsonSplitter::take_buffer() {
  std::unique_ptr<std::string> buffer;
  {
    const std::lock_guard lock(pool_->mutex);
    if (!pool_->free.empty()) {
      buffer = std::move(pool_->free.back());
      pool_->free.pop_back();
    }
  }
  if (!buffer) buffer = std::make_unique<std::string>();
  return std::shared_ptr<std::string>(buffer.release(), [pool = pool_](std::string* text) {
    std::unique_ptr<std::string> owned(text);
    try {
      const std::lock_guard lock(pool->mutex);
      pool->free.push_back(std::move(owned));
    } catch (...) {  // no room to keep it: it is freed
    }
  });
}

JsonSplitter::JsonSplitter(std::map<std::string, char, std::less<>> split, std::size_t run_bytes,
                           std::size_t window_bytes)
    : split_(std::move(split)),
      run_bytes_(std::max<std::size_t>(run_bytes, 1)),
      window_bytes_(std::max<std::size_t>(window_bytes, 1)),
      pool_(std::make_shared<BufferPool>()) {}

bool JsonSplitter::next(const Source& source, std::uint64_t max_bytes, SplitWindow& out, bool& done,
                        std::string& skeleton) {
  std::shared_ptr<std::string> window = take_buffer();
  window->assign(carry_);
  carry_.clear();
  const std::size_t kept = window->size();
  window->resize(kept + window_bytes_);
  std::size_t got = 0;
  while (got < window_bytes_) {
    const std::size_t n = source(window->data() + kept + got, window_bytes_ - got);
    if (n == 0) break;
    got += n;
  }
  window->resize(kept + got);
  total_ += got;
  if (total_ > max_bytes) return false;
  runs_.clear();
  if (!scan(*window, kept, window->size(), skeleton)) return false;
  done = got < window_bytes_;
  if (splitting_ && !done && run_commas_ > 0) {
    // Hand over the open run's whole members; the one the window cuts waits for the next.
    runs_.push_back(container_);
    runs_.back().members = commas_at_last_;
    runs_.back().text = std::string_view(*window).substr(run_start_, last_comma_ - run_start_);
    container_.first += commas_at_last_;
    run_start_ = last_comma_ + 1;
    run_commas_ -= commas_at_last_;
  }
  // A scene's members and skeleton are short: one longer than this is not a document the
  // scan is for (and carrying it from window to window would copy it again each time).
  const std::size_t limit = std::max(window_bytes_, kMaxPieceBytes);
  if (skeleton.size() > limit || (splitting_ && window->size() - run_start_ > limit)) return false;
  if (splitting_ && !done) {
    carry_.assign(*window, run_start_);
    last_comma_ = run_commas_ > 0 ? last_comma_ - run_start_ : 0;
    run_start_ = 0;
  }
  out.runs = std::move(runs_);
  runs_ = {};
  out.text = std::move(window);
  return !done || (depth_ == 0 && !splitting_ && !in_string_);
}

void JsonSplitter::end_run(const std::string& window, std::size_t end, bool last) {
  std::size_t members = run_commas_ + 1;
  const std::string_view text = std::string_view(window).substr(run_start_, end - run_start_);
  if (last && container_.first == 0 && run_commas_ == 0 &&
      std::all_of(text.begin(), text.end(), is_json_space<char>)) {
    members = 0;  // an empty container
  }
  if (members > 0) {
    runs_.push_back(container_);
    runs_.back().members = members;
    runs_.back().text = text;
  }
  container_.first += members;
  run_start_ = end + 1;
  run_commas_ = 0;
}

bool JsonSplitter::container_byte(const std::string& window, std::size_t at) {
  const char c = window[at];
  if (c == '{' || c == '[') {
    ++inner_depth_;
  } else if (c == '}' || c == ']') {
    if (inner_depth_ > 0) {
      --inner_depth_;
      return false;
    }
    end_run(window, at, true);  // the container closes
    splitting_ = false;
    --depth_;
    return true;
  } else if (inner_depth_ == 0) {  // a comma between two members
    if (at - run_start_ >= run_bytes_) {
      end_run(window, at, false);
    } else {
      ++run_commas_;
      last_comma_ = at;
      commas_at_last_ = run_commas_;
    }
  }
  return false;
}

void JsonSplitter::scan_block(const std::string& window, std::size_t& i, std::size_t& copied,
                              std::size_t& bytewise_until) {
  // 64 bytes at once, visiting only the structural bytes outside strings. A block with a
  // backslash goes byte by byte (escapes are rare in a scene file), and so does the byte
  // after one.
  const JsonByteMasks block = classify_json_bytes(window.data() + i);
  if (block.backslash != 0) {
    bytewise_until = i + 64;
    return;
  }
  const std::uint64_t strings = json_string_bytes(block.quote, in_string_);
  std::uint64_t structural = (block.open | block.close | block.comma) & ~strings;
  while (structural != 0) {
    const std::size_t at = i + std::size_t(std::countr_zero(structural));
    structural &= structural - 1;
    if (container_byte(window, at)) {
      copied = at;
      in_string_ = false;
      i = at + 1;
      return;
    }
  }
  in_string_ = (strings >> 63) != 0;
  i += 64;
}

bool JsonSplitter::root_byte(const std::string& window, std::size_t i, std::size_t copied,
                             std::string& skeleton) {
  const char c = window[i];
  if (c == '"') {
    in_string_ = true;
    if (depth_ == 1 && expect_value_) {
      expect_value_ = false;
    } else if (depth_ == 1 && expect_key_) {
      in_key_ = true, key_escaped_ = false, expect_key_ = false;
      key_.clear();
    }
  } else if (c == '{' || c == '[') {
    if (depth_ == 0 && c != '{') return false;  // the root must be an object
    if (depth_ == 0) expect_key_ = true;
    const bool value_of_key = depth_ == 1 && expect_value_;
    expect_value_ = false;
    ++depth_;
    const auto it = value_of_key ? split_.find(key_) : split_.end();
    if (it != split_.end() && it->second == c) {
      skeleton.append(window.data() + copied, i + 1 - copied);
      splitting_ = true;
      container_ = MemberRun{key_, c == '{', 0, 0, {}};
      inner_depth_ = 0;
      run_start_ = i + 1;
      run_commas_ = 0;
    }
  } else if (c == '}' || c == ']') {
    if (--depth_ < 0) return false;
  } else if (c == ',') {
    if (depth_ == 1) expect_key_ = true;
  } else if (c == ':') {
    if (depth_ == 1) {
      if (key_escaped_) return false;  // the scan does not decode escapes: leave it whole
      expect_value_ = true;
    }
  } else if (!is_json_space(c)) {
    if (depth_ == 1) expect_value_ = false;  // a number or a literal
  }
  return true;
}

bool JsonSplitter::scan(const std::string& window, std::size_t from, std::size_t to,
                        std::string& skeleton) {
  const char* data = window.data();
  std::size_t copied = from;  // the skeleton holds the window's bytes before this
  std::size_t i = from;
  std::size_t bytewise_until = from;  // a block with an escape is scanned byte by byte
  while (i < to) {
    if (splitting_ && !escaped_ && i >= bytewise_until && to - i >= 64) {
      scan_block(window, i, copied, bytewise_until);
      continue;
    }
    if (escaped_) {  // the byte after a backslash in a string
      escaped_ = false;
      ++i;
      continue;
    }
    if (in_string_) {
      const std::size_t stop = skip_until(data, i, to, kStringStops);
      if (in_key_) key_.append(data + i, stop - i);
      i = stop;
      if (i == to) break;
      if (data[i] == '\\') {
        escaped_ = true;
        key_escaped_ = key_escaped_ || in_key_;
      } else {
        in_string_ = in_key_ = false;
      }
      ++i;
      continue;
    }
    if (splitting_) {
      i = skip_until(data, i, to, kContainerStops);
      if (i == to) break;
      if (data[i] == '"') {
        in_string_ = true;
      } else if (container_byte(window, i)) {
        copied = i;
      }
      ++i;
      continue;
    }
    // Outside the split containers: the root's structure, byte by byte (it is short).
    if (!root_byte(window, i, copied, skeleton)) return false;
    ++i;
  }
  if (!splitting_) skeleton.append(data + copied, to - copied);
  return true;
}

}  // namespace rtiow
