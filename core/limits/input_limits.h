#pragma once
// The ranges rtiow accepts, in one place. Every input (scene files, command-line values,
// part files, output paths) is checked against these before any work, and the README lists
// them. Each number says why it is what it is.

#include <cstddef>
#include <cstdint>
#include <limits>

namespace rtiow::limits {

// Embree asserts on a ray whose origin or direction has a component beyond 1.844e18
// (FLT_LARGE). Scene coordinates and lengths stay three orders of magnitude below, so
// that the sums a render takes (a centre plus a radius, a camera plus its film) stay
// traceable; camera rays are checked themselves against kMaxRayComponent.
inline constexpr double kMaxCoordinate = 1e15;
inline constexpr double kMaxRayComponent = 1e18;

// The smallest sphere radius: float's smallest normal. Embree's build flushes denormals to
// zero, so a smaller sphere's box would collapse there, and Embree would miss the sphere the
// naive loop finds.
inline constexpr float kMinRadius = std::numeric_limits<float>::min();

// Indices of refraction the extremes tests render without NaN (the book's glass is 1.5,
// real materials lie within 1 to 4).
inline constexpr double kMinIor = 1e-3, kMaxIor = 1e6;

// Image sizes: each side at most 2^20 pixels, and at most 2^31 pixels (beyond, pixel indices
// overflow); the memory an image needs is checked against the machine's
// (core/limits/image_size.h).
inline constexpr int kMaxImageSide = 1 << 20;
inline constexpr std::uint64_t kMaxPixels = std::uint64_t(1) << 31;
inline constexpr int kMaxDepth = 1 << 16;
inline constexpr int kMaxThreads = 1024;  // beyond, TBB's pool refuses or crashes

// Sample indices: a share of a render names samples A..B-1 with B at most 2^32 (the
// samplers index samples with 32 bits).
inline constexpr std::uint64_t kMaxSampleIndex = std::uint64_t(1) << 32;

// The most samples a pixel takes under --adaptive, whose --spp is a budget, not a cap.
inline constexpr std::uint32_t kMostAdaptiveSamples = 1u << 24;

// Scene files: read as a stream (memory grows with the spheres, not the text), but no file
// is read past this size, nested deeper than this, or holds a string longer than this.
inline constexpr std::uint64_t kMaxSceneFileBytes = std::uint64_t(2) << 30;  // 2 GiB
inline constexpr int kMaxJsonDepth = 32;
inline constexpr std::size_t kMaxJsonStringBytes = 4096;

// Part files: far larger than any share of a 2^20 x 2^20 render cannot be a part.
inline constexpr std::uint64_t kMaxPartFileBytes = std::uint64_t(64) << 30;

// Images read (parts, diff's inputs, --like, a cached reference): their header is checked
// before any pixel is allocated, against what a file of its size and format can hold
// (core/io/image_expansion.h: each format's best compression). Below 64 MiB of pixels any
// header is read: that much is cheap, and a flat image of that size may compress further.
inline constexpr std::uint64_t kImageBytesAlwaysRead = std::uint64_t(64) << 20;
// A part file holds 3 + 36 channels, and 28 more with passes (core/render/render_part.h); no
// image rtiow reads more.
inline constexpr std::size_t kMaxImageChannels = 72;

// Echoed values in an error line are cut to this many characters.
inline constexpr std::size_t kMaxEchoedChars = 80;

}  // namespace rtiow::limits
