// The 64-byte classifier the scene scan uses (core/scene_file/json_byte_masks.h) against a byte
// at a time, on random blocks dense in the bytes it looks for and the bytes it must not take
// for them.

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>

#include "core/scene_file/json_byte_masks.h"

namespace rtiow {
namespace {

TEST(JsonByteMasks, ClassifyEveryByteAsAByteAtATimeDoes) {
  // ';' '=' 'K' 'M' 'y' are the bytes one bit away from the structural ones.
  const std::string alphabet = "\"\\{}[],:;=KMy a0\x7f\x80\xfb\xfd";
  std::mt19937 rng(64);
  for (int trial = 0; trial < 20000; ++trial) {
    char block[64];
    for (char& c : block) c = alphabet[rng() % alphabet.size()];
    const JsonByteMasks m = classify_json_bytes(block);
    for (int i = 0; i < 64; ++i) {
      const char c = block[i];
      const auto bit = [&](std::uint64_t mask) { return (mask >> i) & 1; };
      ASSERT_EQ(bit(m.quote), c == '"') << i;
      ASSERT_EQ(bit(m.backslash), c == '\\') << i;
      ASSERT_EQ(bit(m.open), c == '{' || c == '[') << i;
      ASSERT_EQ(bit(m.close), c == '}' || c == ']') << i;
      ASSERT_EQ(bit(m.comma), c == ',') << i;
    }
  }
}

TEST(JsonByteMasks, StringBytesAreThoseAfterAnOddNumberOfQuotes) {
  std::mt19937_64 rng(65);
  for (int trial = 0; trial < 20000; ++trial) {
    const std::uint64_t quotes = rng() & rng();  // about one byte in four
    const bool begins_in_string = (trial & 1) != 0;
    const std::uint64_t in = json_string_bytes(quotes, begins_in_string);
    bool inside = begins_in_string;
    for (int i = 0; i < 64; ++i) {
      if ((quotes >> i) & 1) inside = !inside;
      ASSERT_EQ((in >> i) & 1, inside ? 1u : 0u) << "byte " << i << ", trial " << trial;
    }
  }
}

}  // namespace
}  // namespace rtiow
