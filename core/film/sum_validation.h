#pragma once
// The one check of a pixel's sums read from outside the process (a checkpoint, a part file):
// whether `samples` samples of indices [first, first + samples) can add up to them. Every
// group's channel must lie within what its samples can add (core/film/sum_channels.h); the
// odd samples' sum within the samples' sum; the squares no less than the two replicates' sums
// force (Cauchy-Schwarz, for each replicate) and no more than the samples can square; a sum of
// unit normals no longer than its samples. So a word changed in a file is refused by name,
// whichever reader meets it, rather than merged into a pixel no render can make.

#include <cstdint>
#include <string>

#include "core/film/sum_channels.h"

namespace rtiow {

// Empty when the sums are possible; otherwise why not, naming the channel ("sum.R is beyond
// what 2 samples can add up to").
std::string impossible_sums(const PixelSumsRef& sums, std::uint64_t first, std::uint64_t samples);

}  // namespace rtiow
