#pragma once
// The hot loops (the sample loop, the camera's rays, the sphere test Embree calls back, the
// loops that walk four pixels a lane: core/parallel/lanes.h) are compiled for three x86-64
// levels and the best the CPU has is chosen when the program loads (GCC's target_clones, an
// ifunc): a portable build, an installed library or a package runs on any x86-64 and still
// uses AVX2 or AVX-512 where they are there. Every level computes the
// same bits: no FMA contraction and no fast-math (cmake/Warnings.cmake), so only the width of
// the vector instructions differs. A -march=native build (RTIOW_NATIVE) needs no choice.

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(RTIOW_NO_DISPATCH)
#define RTIOW_DISPATCHED [[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]]
#else
#define RTIOW_DISPATCHED
#endif
