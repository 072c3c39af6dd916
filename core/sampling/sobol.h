#pragma once
// Owen-scrambled Sobol points for the first dimensions of a pixel sample. Point i of
// dimension d is a pure function of (i, d, scramble seed): nothing depends on how many
// samples the render takes, so a time-limited, adaptive or shared render draws the same
// points as a fixed one. Every power-of-two prefix of a dimension fills its strata, and
// dimensions 0 and 1 form a (0,2)-sequence: any 2^m consecutive-from-zero points put one
// point in each of the 2^m elementary intervals of every shape.
//
// The generator matrices come from Joe and Kuo's direction numbers (new-joe-kuo-6.21201,
// dimensions 2-16; dimension 1 is van der Corput's). The scramble is the hash-based nested
// permutation of Laine and Karras with Vegdahl's constants (Burley 2020): each step only
// lets higher-order bits of the reversed value depend on lower ones, which is what makes
// it an Owen (nested uniform) scramble.

#include <array>
#include <cstddef>
#include <cstdint>

namespace rtiow {

// The camera's four and three bounces' four each (core/sampling/sample_layout.h).
inline constexpr int kSobolDimensions = 16;

constexpr std::uint32_t reverse_bits(std::uint32_t x) {
  x = __builtin_bswap32(x);
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  return ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
}

namespace sobol_detail {

struct PrimitivePolynomial {
  int degree;
  std::uint32_t coefficients;            // a_1 .. a_{s-1}, the highest first
  std::array<std::uint32_t, 6> initial;  // m_1 .. m_s
};

// Dimensions 1..15 (the table's dimensions 2..16).
constexpr std::array<PrimitivePolynomial, kSobolDimensions - 1> kJoeKuo{{
    {1, 0, {1}},
    {2, 1, {1, 3}},
    {3, 1, {1, 3, 1}},
    {3, 2, {1, 1, 1}},
    {4, 1, {1, 1, 3, 3}},
    {4, 4, {1, 3, 5, 13}},
    {5, 2, {1, 1, 5, 5, 17}},
    {5, 4, {1, 1, 5, 5, 5}},
    {5, 7, {1, 1, 7, 11, 19}},
    {5, 11, {1, 1, 5, 1, 1}},
    {5, 13, {1, 1, 1, 3, 11}},
    {5, 14, {1, 3, 5, 5, 31}},
    {6, 1, {1, 3, 3, 9, 7, 49}},
    {6, 13, {1, 1, 1, 15, 21, 21}},
    {6, 16, {1, 3, 1, 13, 27, 49}},
}};

using Matrix = std::array<std::uint32_t, 32>;  // column k: the contribution of index bit k

constexpr Matrix generator_matrix(int dimension) {
  Matrix v{};
  if (dimension == 0) {
    for (int k = 0; k < 32; ++k) v[k] = 1u << (31 - k);
    return v;
  }
  const PrimitivePolynomial& p = kJoeKuo[dimension - 1];
  const int s = p.degree;
  for (int k = 0; k < s; ++k) v[k] = p.initial[k] << (31 - k);
  for (int k = s; k < 32; ++k) {
    std::uint32_t x = v[k - s] ^ (v[k - s] >> s);
    for (int j = 1; j < s; ++j) {
      if ((p.coefficients >> (s - 1 - j)) & 1u) x ^= v[k - j];
    }
    v[k] = x;
  }
  return v;
}

constexpr std::array<Matrix, kSobolDimensions> make_matrices() {
  std::array<Matrix, kSobolDimensions> m{};
  for (int d = 0; d < kSobolDimensions; ++d) m[d] = generator_matrix(d);
  return m;
}

inline constexpr std::array<Matrix, kSobolDimensions> kMatrices = make_matrices();

// The matrix product by bytes, bit-reversed: entry [d][b][v] is the reversed point's
// contribution from byte b of the index having value v, so a point is four lookups instead of
// a loop over the index's bits (a shuffled index has about 16 of them set), and the Owen
// scramble, which works on the reversed bits, needs no reversal going in.
using ByteTables = std::array<std::array<std::array<std::uint32_t, 256>, 4>, kSobolDimensions>;

// Each entry is the entry without its lowest set bit plus that bit's column (reversal commutes
// with XOR), one step per entry: the compile-time evaluation stays within clang's step limit.
constexpr ByteTables make_byte_tables() {
  ByteTables t{};
  for (std::size_t d = 0; d < std::size_t(kSobolDimensions); ++d) {
    for (std::size_t b = 0; b < 4; ++b) {
      for (std::uint32_t v = 1; v < 256; ++v) {
        const auto lowest = std::size_t(__builtin_ctz(v));
        t[d][b][v] = t[d][b][v & (v - 1)] ^ reverse_bits(kMatrices[d][8 * b + lowest]);
      }
    }
  }
  return t;
}

inline constexpr ByteTables kByteTables = make_byte_tables();

}  // namespace sobol_detail

// The unscrambled Sobol point with its bits reversed (the first bit is the lowest): index i's
// bits select columns of the dimension's matrix. `dimension` must be below kSobolDimensions
// (the remainder only tells the compiler so).
constexpr std::uint32_t reversed_sobol_bits(std::uint32_t index, int dimension) {
  const auto& t = sobol_detail::kByteTables[std::size_t(dimension) % kSobolDimensions];
  return t[0][index & 0xffu] ^ t[1][(index >> 8) & 0xffu] ^ t[2][(index >> 16) & 0xffu] ^
         t[3][index >> 24];
}

// The unscrambled Sobol point as a 32-bit fraction.
constexpr std::uint32_t sobol_bits(std::uint32_t index, int dimension) {
  return reverse_bits(reversed_sobol_bits(index, dimension));
}

// Laine and Karras's permutation: bit k of the result depends only on bits 0..k of `x`.
constexpr std::uint32_t laine_karras(std::uint32_t x, std::uint32_t seed) {
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return x;
}

// A nested uniform permutation of the 32-bit fraction `x`, chosen by `seed`: applied to
// the reversed bits, each bit depends only on the bits above it.
constexpr std::uint32_t owen_scramble(std::uint32_t x, std::uint32_t seed) {
  return reverse_bits(laine_karras(reverse_bits(x), seed));
}

constexpr float to_unit_float(std::uint32_t x) {
  return float(x >> 8) * 0x1p-24f;
}

// In [0, 1) with 24 bits, like the independent sampler's floats.
constexpr float scrambled_sobol(std::uint32_t index, int dimension, std::uint32_t seed) {
  return to_unit_float(reverse_bits(laine_karras(reversed_sobol_bits(index, dimension), seed)));
}

// Padded sampling: an index shuffled by a nested scramble of its bits (Burley 2020), which
// maps the first 2^m indices onto an aligned block of 2^m, whose Sobol points are again a
// (0,m,2)-net. `reversed_index` is reverse_bits(index), computed once per sample.
constexpr std::uint32_t shuffled_index(std::uint32_t reversed_index, std::uint32_t seed) {
  return reverse_bits(laine_karras(reversed_index, seed));
}

// Dimension 0 (van der Corput) of a shuffled index, scrambled: Sobol's dimension 0 is the
// reversed index, so the scramble's first reversal cancels it.
constexpr float scrambled_van_der_corput(std::uint32_t index, std::uint32_t seed) {
  return to_unit_float(reverse_bits(laine_karras(index, seed)));
}

}  // namespace rtiow
