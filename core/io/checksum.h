#pragma once
// A 64-bit checksum of a byte stream, eight bytes at a time: it catches a torn or altered
// checkpoint, and tells one scene from another, at a cost beside memory's speed. Not for
// anything an adversary chooses to collide.

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace rtiow {

// A multiply-xorshift over little-endian words; the same bytes give the same value however
// they are split between calls.
class Checksum {
 public:
  void update(const char* data, std::size_t n) {
    std::size_t i = 0;
    for (; i < n && filled_ != 0; ++i) add_byte(data[i]);
    // Whole words at once (the same little-endian word the bytes would make).
    for (; i + 8 <= n; i += 8) {
      std::memcpy(&word_, data + i, 8);
      flush_word();
    }
    for (; i < n; ++i) add_byte(data[i]);
  }
  std::uint64_t value() const {
    std::uint64_t h = state_ ^ (word_ * 0x9e3779b97f4a7c15ull) ^ filled_;
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    return h ^ (h >> 33);
  }

 private:
  void add_byte(char byte) {
    word_ |= std::uint64_t(static_cast<unsigned char>(byte)) << (8 * filled_);
    if (++filled_ == 8) flush_word();
  }
  void flush_word() {
    state_ = (state_ ^ word_) * 0x100000001b3ull;
    state_ ^= state_ >> 29;
    word_ = 0;
    filled_ = 0;
  }
  std::uint64_t state_ = 0xcbf29ce484222325ull, word_ = 0;
  unsigned filled_ = 0;
};

}  // namespace rtiow
