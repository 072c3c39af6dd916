#pragma once
// Counter-based randomness. A pixel sample's random numbers are a pure function of
// (seed, pixel, sample index): each pixel owns a PCG32 sequence chosen by hashing
// (seed, pixel), and sample i starts at a state hashed from (seed, pixel, i). (pbrt-v4's
// IndependentSampler instead jumps 2^16 draws per sample; a hashed start costs two steps
// rather than a 64-step jump, and in a period of 2^64 two samples' streams of a few hundred
// draws overlap with negligible probability.) No state is shared between threads, so any
// schedule gives the same image.

#include <cstdint>

namespace rtiow {

// A 64-bit finaliser (splitmix64): decorrelates nearby integers such as pixel indices.
constexpr std::uint64_t mix64(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  x ^= x >> 31;
  return x;
}

constexpr std::uint64_t hash_combine(std::uint64_t seed, std::uint64_t value) {
  return mix64(seed ^ (mix64(value) + 0x9e3779b97f4a7c15ull + (seed << 6) + (seed >> 2)));
}

// PCG32 (O'Neill): 64-bit LCG state, 32-bit permuted output, 2^63 selectable sequences.
class Pcg32 {
 public:
  constexpr Pcg32() { set_sequence(0, 0x853c49e6748fea9bull); }
  constexpr Pcg32(std::uint64_t sequence, std::uint64_t seed) { set_sequence(sequence, seed); }

  constexpr void set_sequence(std::uint64_t sequence, std::uint64_t seed) {
    state_ = 0;
    inc_ = (sequence << 1u) | 1u;
    next_u32();
    state_ += seed;
    next_u32();
  }

  constexpr std::uint32_t next_u32() {
    const std::uint64_t old = state_;
    state_ = old * kMultiplier + inc_;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
  }

  // Uniform float in [0, 1): the top 24 bits, so every value is exactly representable.
  constexpr float next_float() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }
  constexpr double next_double() {
    const std::uint64_t hi = next_u32(), lo = next_u32();
    return static_cast<double>(((hi << 32) | lo) >> 11) * 0x1p-53;
  }

  constexpr bool operator==(const Pcg32&) const = default;

 private:
  static constexpr std::uint64_t kMultiplier = 0x5851f42d4c957f2dull;
  std::uint64_t state_{};
  std::uint64_t inc_{};
};

}  // namespace rtiow
