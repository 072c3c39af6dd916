#pragma once
// 64 bytes of JSON text classified at once, one bit a byte (bit i for byte i): the quotes,
// backslashes and structural characters a scan for member boundaries looks for, and which
// bytes lie inside strings. Where a byte-at-a-time scan branches on every one of them, a scan
// of these masks touches only the structural characters outside strings (about one byte in
// sixteen of a scene file).

#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace rtiow {

struct JsonByteMasks {
  std::uint64_t quote = 0;      // "
  std::uint64_t backslash = 0;  // '\'
  std::uint64_t open = 0;       // { [
  std::uint64_t close = 0;      // } ]
  std::uint64_t comma = 0;      // ,
};

// '[' and ']' are '{' and '}' without bit 5, and no other byte is: one compare finds both.
inline JsonByteMasks classify_json_bytes(const char* block) {
  JsonByteMasks m;
#if defined(__SSE2__)  // every x86-64 CPU: four 16-byte compares a class
  for (int part = 0; part < 4; ++part) {
    const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(block + 16 * part));
    const __m128i folded = _mm_or_si128(bytes, _mm_set1_epi8(0x20));
    const auto bits = [&](__m128i v, char c) {
      return std::uint64_t(std::uint16_t(_mm_movemask_epi8(_mm_cmpeq_epi8(v, _mm_set1_epi8(c)))))
             << (16 * part);
    };
    m.quote |= bits(bytes, '"');
    m.backslash |= bits(bytes, '\\');
    m.open |= bits(folded, '{');
    m.close |= bits(folded, '}');
    m.comma |= bits(bytes, ',');
  }
#else
  for (int i = 0; i < 64; ++i) {
    const char c = block[i];
    const std::uint64_t bit = std::uint64_t(1) << i;
    if (c == '"') m.quote |= bit;
    if (c == '\\') m.backslash |= bit;
    if ((c | 0x20) == '{') m.open |= bit;
    if ((c | 0x20) == '}') m.close |= bit;
    if (c == ',') m.comma |= bit;
  }
#endif
  return m;
}

// The bytes inside strings, given the block's quotes (none escaped) and whether the block
// begins inside a string: bit i is set when an odd number of quotes lie at or before byte i
// (counting the string the block begins in as one), so an opening quote and a string's
// bytes are in, its closing quote is out.
inline std::uint64_t json_string_bytes(std::uint64_t quotes, bool begins_in_string) {
  std::uint64_t x = quotes;  // prefix XOR: each bit becomes the parity of the bits up to it
  x ^= x << 1;
  x ^= x << 2;
  x ^= x << 4;
  x ^= x << 8;
  x ^= x << 16;
  x ^= x << 32;
  return begins_in_string ? ~x : x;
}

}  // namespace rtiow
