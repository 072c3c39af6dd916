#pragma once
// The sampler, in one place: the numbers a pixel sample draws, dimension by dimension, in
// the fixed layout of core/sampling/sample_layout.h (camera 4, then 4 per bounce).
//
// - independent (the book's): every dimension from the sample's PCG32 stream (rng.h).
// - sobol: the camera and the first bounce (kSobolDimensions = 8) are one Owen-scrambled
//   Sobol point, so pixel, lens and first direction are stratified jointly; every later
//   bounce is padded like padded-sobol.
// - padded-sobol: every 1D and 2D group on its own: a (0,2)-sequence (Sobol dimensions 0
//   and 1) whose sample order is shuffled per (pixel, dimension) and whose values are
//   Owen-scrambled, as pbrt-v4's PaddedSobolSampler and Burley (2020) do. Shuffling by a
//   nested scramble of the index bits (rather than by a permutation of a known count) keeps
//   it open ended: the first 2^m samples map onto an aligned block of 2^m Sobol indices,
//   which is again a (0,m,2)-net.
// All are pure functions of (seed, pixel, sample index, dimension): nothing depends on how
// many samples a render takes or how they are split between threads, passes or processes.

#include <array>
#include <cstdint>
#include <string>

#include "core/sampling/rng.h"
#include "core/sampling/sample_layout.h"
#include "core/sampling/sobol.h"

namespace rtiow {

enum class SamplerKind { Independent, Sobol, PaddedSobol };

std::string to_string(SamplerKind kind);
SamplerKind parse_sampler(const std::string& name);  // throws InvalidInput
// The names parse_sampler knows, comma separated, for help texts and errors.
const char* sampler_names();

class SampleStream {
 public:
  constexpr SampleStream(std::uint64_t seed, std::uint32_t px, std::uint32_t py,
                         std::uint64_t sample_index, SamplerKind kind = SamplerKind::Independent)
      : SampleStream(hash_combine(hash_combine(mix64(seed), px), py), sample_index, kind) {}

  constexpr SampleStream(SamplerKind kind, std::uint64_t seed, std::uint32_t px, std::uint32_t py,
                         std::uint64_t sample_index)
      : SampleStream(seed, px, py, sample_index, kind) {}

  // The next dimension.
  constexpr float next_1d() {
    const int d = dimension_++;
    if (kind_ == SamplerKind::Independent) return rng_.next_float();
    const std::uint64_t h = dimension_hash(d);
    if (is_joint(d)) return scrambled_sobol(index_, d, std::uint32_t(h >> 32));
    return scrambled_van_der_corput(shuffled_index(reversed_index_, std::uint32_t(h)),
                                    std::uint32_t(h >> 32));
  }

  // The next two dimensions, as one 2D group.
  constexpr std::array<float, 2> next_2d() {
    const int d = dimension_;
    if (kind_ == SamplerKind::Independent || is_joint(d)) {
      const float u = next_1d();
      return {u, next_1d()};
    }
    dimension_ += 2;
    const std::uint64_t h = dimension_hash(d);
    const std::uint32_t i = shuffled_index(reversed_index_, std::uint32_t(h));
    return {scrambled_van_der_corput(i, std::uint32_t(h >> 32)),
            scrambled_sobol(i, 1, std::uint32_t((h * 0xd1342543de82ef95ull) >> 32))};
  }

  // The camera's four dimensions: film position, then lens.
  constexpr std::array<float, 4> next_camera() {
    const auto film = next_2d(), lens = next_2d();
    return {film[0], film[1], lens[0], lens[1]};
  }

  // One bounce's dimensions. The independent sampler draws all four from its stream (cheap,
  // and its order stays fixed); the others compute the ones in `uses` and leave the rest 0.
  constexpr BounceSample next_bounce(unsigned uses = kUsesAll) {
    if (kind_ == SamplerKind::Independent) uses = kUsesAll;
    const int d = dimension_;
    BounceSample b;
    if (uses & kUsesDirection) {
      const auto direction = next_2d();
      b.direction[0] = direction[0], b.direction[1] = direction[1];
    }
    dimension_ = d + 2;
    if (uses & kUsesLobe) b.lobe = next_1d();
    dimension_ = d + 3;
    if (uses & kUsesRadius) b.radius = next_1d();
    dimension_ = d + kBounceDimensions;
    return b;
  }

  // How many dimensions have been drawn.
  constexpr int dimension() const { return dimension_; }

 private:
  constexpr SampleStream(std::uint64_t pixel_hash, std::uint64_t sample_index, SamplerKind kind)
      : rng_(pixel_hash, hash_combine(pixel_hash, sample_index)),
        pixel_hash_(pixel_hash),
        index_(std::uint32_t(sample_index)),
        reversed_index_(reverse_bits(std::uint32_t(sample_index))),
        kind_(kind) {}

  constexpr bool is_joint(int d) const {
    return kind_ == SamplerKind::Sobol && d < kSobolDimensions;
  }
  // Each dimension's scrambles (and shuffle): one finaliser of (pixel, dimension).
  constexpr std::uint64_t dimension_hash(int d) const {
    return mix64(pixel_hash_ + 0x9e3779b97f4a7c15ull * std::uint64_t(d + 1));
  }

  Pcg32 rng_;
  std::uint64_t pixel_hash_;
  std::uint32_t index_;
  std::uint32_t reversed_index_;
  SamplerKind kind_;
  int dimension_ = 0;
};

}  // namespace rtiow
