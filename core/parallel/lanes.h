#pragma once
// Four doubles side by side, one pixel per lane, for the loops that walk four neighbouring
// pixels at once: GCC's vector extension, whose arithmetic is each lane's own IEEE operation,
// so every lane computes the bits one pixel at a time would (no FMA contraction:
// cmake/Warnings.cmake). One AVX register in the AVX2 and AVX-512 clones of the hot loops
// (core/parallel/instruction_sets.h), two SSE2 registers in the baseline. Pass them only into
// and out of dispatched functions by reference (their by-value ABI differs between the two).

#include <cstdint>

namespace rtiow {

inline constexpr int kLanes = 4;
using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));
// A comparison's result, and the bits that mask a lane out: value & keep is +0.0 where keep
// is 0, which adds nothing to any sum and cannot become NaN.
using LaneMask = std::int64_t __attribute__((vector_size(kLanes * sizeof(double))));

}  // namespace rtiow
