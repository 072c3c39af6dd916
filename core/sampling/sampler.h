#pragma once
// The sampler, in one place: the numbers a pixel sample draws, dimension by dimension, in
// the fixed layout of core/sampling/sample_layout.h (camera 4, then 4 per bounce).
//
// - independent (the book's): every dimension from the sample's PCG32 stream (rng.h).
// - sobol: the camera and the first three bounces (kSobolDimensions = 16) are one
//   Owen-scrambled Sobol point, so pixel, lens and the first directions are stratified
//   jointly; every later bounce is padded like padded-sobol.
// - padded-sobol: every 1D and 2D group on its own: a (0,2)-sequence (Sobol dimensions 0
//   and 1) whose sample order is shuffled per (pixel, dimension) and whose values are
//   Owen-scrambled, as pbrt-v4's PaddedSobolSampler and Burley (2020) do. Shuffling by a
//   nested scramble of the index bits (rather than by a permutation of a known count) keeps
//   it open ended: the first 2^m samples map onto an aligned block of 2^m Sobol indices,
//   which is again a (0,m,2)-net.
// All are pure functions of (seed, pixel, sample index, dimension): nothing depends on how
// many samples a render takes or how they are split between threads, passes or processes.
//
// Replicates: where a render estimates its own error, a pixel's samples alternate between two
// independently scrambled sequences (even sample indices draw point i/2 of the first, odd ones
// point i/2 of the second). The mean of a scrambled Sobol sequence converges faster than 1/n,
// so a pixel's own sample variance overstates its error; the spread of two independent
// replicates' means does not (core/film/replicate_variance.h). Two sequences of n/2 points are
// noisier than one of n (1.18-1.23x the relMSE on the cover at 64-500 spp), so a render that
// estimates nothing draws sample i from point i of one sequence (the first replicate's). The
// independent sampler's samples are replicates as they are.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/sampling/rng.h"
#include "core/sampling/sample_layout.h"
#include "core/sampling/sobol.h"

namespace rtiow {

enum class SamplerKind { Independent, Sobol, PaddedSobol };

std::string to_string(SamplerKind kind);
SamplerKind parse_sampler(const std::string& name);  // throws InvalidInput
// The names parse_sampler knows, comma separated, for help texts and errors.
const char* sampler_names();
// The same names one by one, for an option's list of choices.
std::vector<std::string> sampler_name_list();

// A pixel's hash of (seed, pixel).
constexpr std::uint64_t pixel_hash(std::uint64_t seed, std::uint32_t px, std::uint32_t py) {
  return hash_combine(hash_combine(mix64(seed), px), py);
}

// How many independent replicates a pixel's samples alternate between, and which one and
// which point of it sample `i` is.
inline constexpr int kReplicates = 2;
// `replicates` is kReplicates, or 1 for one sequence.
constexpr int replicate_of(std::uint64_t sample_index, int replicates = kReplicates) {
  return replicates == 1 ? 0 : int(sample_index & 1u);
}
constexpr std::uint64_t point_in_replicate(std::uint64_t sample_index,
                                           int replicates = kReplicates) {
  return replicates == 1 ? sample_index : sample_index >> 1;
}

// The second replicate's scrambles come from its own hash of the pixel.
constexpr std::uint64_t replicate_hash(std::uint64_t pixel_hash, int replicate) {
  return replicate == 0 ? pixel_hash : mix64(pixel_hash ^ 0xa0761d6478bd642full);
}

// Each dimension's scrambles (and shuffle) for a pixel: one finaliser of (pixel, dimension).
constexpr std::uint64_t dimension_hash(std::uint64_t pixel_hash, int d) {
  return mix64(pixel_hash + 0x9e3779b97f4a7c15ull * std::uint64_t(d + 1));
}

// What all samples of a pixel share: its hash and, per replicate, the hashes of its first
// dimensions, which depend on the pixel and the dimension but not on the sample. Made once per
// pixel, they save a sample some twenty 64-bit finalisers (about 8% of a Sobol sample's time
// on the cover).
struct PixelSampler {
  static constexpr int kCachedDimensions = 16;  // the camera and three bounces

  SamplerKind kind;
  std::uint64_t hash;
  int replicates;  // kReplicates, or 1 (one sequence)
  std::array<std::uint64_t, kReplicates> replicate_hashes{};
  std::array<std::array<std::uint64_t, kCachedDimensions>, kReplicates> dimension_hashes{};

  constexpr PixelSampler(SamplerKind kind_, std::uint64_t seed, std::uint32_t px, std::uint32_t py,
                         int replicates_ = kReplicates)
      : kind(kind_), hash(pixel_hash(seed, px, py)), replicates(replicates_) {
    if (kind == SamplerKind::Independent) return;  // it draws from its stream alone
    for (int r = 0; r < replicates; ++r) {
      replicate_hashes[std::size_t(r)] = replicate_hash(hash, r);
      for (int d = 0; d < kCachedDimensions; ++d) {
        dimension_hashes[std::size_t(r)][std::size_t(d)] =
            dimension_hash(replicate_hashes[std::size_t(r)], d);
      }
    }
  }
};

class SampleStream {
 public:
  constexpr SampleStream(std::uint64_t seed, std::uint32_t px, std::uint32_t py,
                         std::uint64_t sample_index, SamplerKind kind = SamplerKind::Independent)
      : SampleStream(pixel_hash(seed, px, py), nullptr, nullptr, sample_index, kind) {}

  constexpr SampleStream(SamplerKind kind, std::uint64_t seed, std::uint32_t px, std::uint32_t py,
                         std::uint64_t sample_index)
      : SampleStream(seed, px, py, sample_index, kind) {}

  // Sample `sample_index` of the pixel; `pixel` must outlive the stream.
  constexpr SampleStream(const PixelSampler& pixel, std::uint64_t sample_index)
      : SampleStream(
            pixel.hash,
            &pixel.replicate_hashes[std::size_t(replicate_of(sample_index, pixel.replicates))],
            pixel.dimension_hashes[std::size_t(replicate_of(sample_index, pixel.replicates))]
                .data(),
            sample_index, pixel.kind, pixel.replicates) {}

  // The next dimension.
  constexpr float next_1d() {
    const int d = dimension_++;
    if (kind_ == SamplerKind::Independent) return rng_.next_float();
    const std::uint64_t h = hash_of(d);
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
    const std::uint64_t h = hash_of(d);
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
    dimension_ = d + kDirectionOffset;
    if (uses & kUsesDirection) {
      const auto direction = next_2d();
      b.direction[0] = direction[0], b.direction[1] = direction[1];
    }
    dimension_ = d + kLobeOffset;
    if (uses & kUsesLobe) b.lobe = next_1d();
    dimension_ = d + kRadiusOffset;
    if (uses & kUsesRadius) b.radius = next_1d();
    dimension_ = d + kBounceDimensions;
    return b;
  }

  // How many dimensions have been drawn.
  constexpr int dimension() const { return dimension_; }

 private:
  // `cached_replicate_hash` and `cached_hashes`, when given, are the sample's replicate's.
  constexpr SampleStream(std::uint64_t pixel_hash, const std::uint64_t* cached_replicate_hash,
                         const std::uint64_t* cached_hashes, std::uint64_t sample_index,
                         SamplerKind kind, int replicates = kReplicates)
      : pixel_hash_(pixel_hash),
        cached_hashes_(cached_hashes),
        index_(std::uint32_t(point_in_replicate(sample_index, replicates))),
        reversed_index_(reverse_bits(index_)),
        kind_(kind) {
    // Only the independent sampler reads the stream: the others skip its set-up.
    if (kind == SamplerKind::Independent) {
      rng_.set_sequence(pixel_hash, hash_combine(pixel_hash, sample_index));
    } else {
      pixel_hash_ = cached_replicate_hash
                        ? *cached_replicate_hash
                        : replicate_hash(pixel_hash, replicate_of(sample_index, replicates));
    }
  }

  constexpr bool is_joint(int d) const {
    return kind_ == SamplerKind::Sobol && d < kSobolDimensions;
  }
  constexpr std::uint64_t hash_of(int d) const {
    return cached_hashes_ && d < PixelSampler::kCachedDimensions ? cached_hashes_[d]
                                                                 : dimension_hash(pixel_hash_, d);
  }

  Pcg32 rng_{};
  std::uint64_t pixel_hash_;  // the replicate's, for the Sobol samplers
  const std::uint64_t* cached_hashes_;
  std::uint32_t index_;
  std::uint32_t reversed_index_;
  SamplerKind kind_;
  int dimension_ = 0;
};

}  // namespace rtiow
