#pragma once
// How many samples a render takes per pixel, and what ends it. The number a user gives with
// --spp means a count, a budget or a cap depending on the mode beside it; each meaning is its
// own type here, so a consumer reads which one it has instead of re-deriving it.

#include <cstdint>
#include <optional>
#include <variant>

namespace rtiow {

// The fewest samples an adaptive mode gives a pixel before judging it (--min-spp).
inline constexpr int kDefaultLeastSamples = 16;

// The most samples a pixel takes under an error target when nothing else caps it (--spp).
inline constexpr int kDefaultErrorDrivenMaxSpp = 8192;

// Every pixel exactly `per_pixel` samples (fewer if a time limit or a stop ends it first).
struct FixedSamples {
  int per_pixel = 1;
};

// Every pixel the same count, in passes until the time limit ends the render.
struct UntilTimeLimit {};

// --adaptive: the cost of `per_pixel` uniform samples (none: of the time limit alone),
// allocated to the pixels by their variance and cost, each at least `least`.
struct AdaptiveBudget {
  std::optional<int> per_pixel;
  int least = kDefaultLeastSamples;
};

// --target-error: each pixel until its relative standard error is below `error`, from
// `least` samples up to `most`.
struct PixelErrorTarget {
  double error = 0.0;
  int most = kDefaultErrorDrivenMaxSpp;
  int least = kDefaultLeastSamples;
};

// --image-error: until the image's estimated relative RMS error is below `error`, each pixel
// from `least` samples up to `most`.
struct ImageErrorTarget {
  double error = 0.0;
  int most = kDefaultErrorDrivenMaxSpp;
  int least = kDefaultLeastSamples;
  // The denoised image's error (--image-error with --denoise): every pixel takes the same
  // count, each round as many as the denoiser's estimate says the target needs
  // (core/render/denoised_rounds.h).
  bool denoised = false;
};

using SampleBudget =
    std::variant<FixedSamples, UntilTimeLimit, AdaptiveBudget, PixelErrorTarget, ImageErrorTarget>;

// Whether pixels get different sample counts.
inline bool is_adaptive(const SampleBudget& b) {
  return !std::holds_alternative<FixedSamples>(b) && !std::holds_alternative<UntilTimeLimit>(b);
}

// The --spp a user gave for this budget: the count, the budget or the cap; none when only
// the time limit bounds the render.
inline std::optional<int> spp_option(const SampleBudget& b) {
  if (const auto* f = std::get_if<FixedSamples>(&b)) return f->per_pixel;
  if (const auto* a = std::get_if<AdaptiveBudget>(&b)) return a->per_pixel;
  if (const auto* t = std::get_if<PixelErrorTarget>(&b)) return t->most;
  if (const auto* i = std::get_if<ImageErrorTarget>(&b)) return i->most;
  return std::nullopt;
}

// The adaptive minimum (--min-spp); none for a uniform render.
inline std::optional<int> least_samples(const SampleBudget& b) {
  if (const auto* a = std::get_if<AdaptiveBudget>(&b)) return a->least;
  if (const auto* t = std::get_if<PixelErrorTarget>(&b)) return t->least;
  if (const auto* i = std::get_if<ImageErrorTarget>(&b)) return i->least;
  return std::nullopt;
}

}  // namespace rtiow
