#pragma once
// What the denoiser reads: each pixel's two independent halves of its samples (the even and the
// odd sample indices, drawn from the sampler's two independent replicates), how many samples
// each half holds, and the first hit's albedo, normal and depth over all the samples. All of it
// is taken from a render's exact sums (or a merge of its parts) and rounded once to float, so the
// same render gives the denoiser the same input however it was made: in one process, from
// checkpoints, from part files, under MPI, on any number of threads
// (core/render/denoised_output.h makes it from a render's result).

#include <array>
#include <cstdint>
#include <vector>

#include "core/film/first_hit_sum.h"
#include "core/geometry/vec3.h"

namespace rtiow {

// albedo R, G, B; normal X, Y, Z; depth: FirstHitSum's channels, as means.
using PixelFeatures = std::array<float, FirstHitSum::kChannels>;

struct DenoiseInput {
  int width = 0, height = 0;
  std::vector<Color> mean;       // the noisy image: the mean of all the samples, row major
  std::vector<Color> even, odd;  // each half's mean
  std::vector<std::uint32_t> even_samples, odd_samples;
  std::vector<PixelFeatures> features;

  std::size_t size() const { return even.size(); }
};

}  // namespace rtiow
