#pragma once
// Which render this is: what must agree for a checkpoint to continue a render, for shares
// (part files, MPI ranks) to add up to one, and for a cached reference to stand for another.
// Declared once, in the library's own words: the checkpoint's header keys, the part files'
// digest and every "what differs" message follow this table, so a file format never depends
// on how a front end spells its options.

#include <array>
#include <cstddef>
#include <string>

#include "core/render/render_settings.h"
#include "core/scene/scene.h"

namespace rtiow {

enum class IdentityField : std::size_t {
  Version,      // rtiow's: the sample streams may change between versions
  Scene,        // a digest of the scene, its camera and materials included
  Size,         // "WxH", with " crop x0,y0,x1,y1" for a region of that frame
  Depth,        // the most bounces a path takes
  Seed,         // of the sample streams
  Sampler,      // "sobol", "independent"
  Replicates,   // "2", or "1" for one sequence (other samples than two replicates)
  Roulette,     // "on", "off": other paths end, other samples follow
  FirstSample,  // where a share of the samples starts
  Sampling,     // "uniform", or the adaptive mode with its parameters
  Passes,       // whether the first hit's sums are kept
};

struct IdentityFieldDeclaration {
  IdentityField field;
  const char* key;    // in files (a checkpoint's header)
  const char* label;  // in messages
  bool shared;        // whether every share of one render has it (then it is in the digest)
};

inline constexpr std::array<IdentityFieldDeclaration, 11> kIdentityFields = {{
    {IdentityField::Version, "version", "rtiow version", false},  // merge names it first
    {IdentityField::Scene, "scene", "scene", true},
    {IdentityField::Size, "size", "image size", true},
    {IdentityField::Depth, "depth", "depth", true},
    {IdentityField::Seed, "seed", "seed", true},
    {IdentityField::Sampler, "sampler", "sampler", true},
    {IdentityField::Replicates, "replicates", "replicates", true},
    {IdentityField::Roulette, "roulette", "Russian roulette", true},
    {IdentityField::FirstSample, "first_sample", "first sample", false},
    {IdentityField::Sampling, "sampling", "sampling", false},
    {IdentityField::Passes, "passes", "passes", false},
}};

// Each field's value as text, in kIdentityFields' order.
struct RenderIdentity {
  std::array<std::string, kIdentityFields.size()> values;

  std::string& operator[](IdentityField f) { return values[std::size_t(f)]; }
  const std::string& operator[](IdentityField f) const { return values[std::size_t(f)]; }
  bool operator==(const RenderIdentity&) const = default;
};

// The identity of rendering `scene` with `settings` (their size and depth resolved).
RenderIdentity render_identity(const Scene& scene, const RenderSettings& settings);

// How a budget of samples reads in an identity: "uniform", "pixel error 0.05, 16 to 64
// samples", "image error 0.01, 16 to 8192 samples", "adaptive, 64 samples a pixel, at least
// 16", "adaptive, within the time limit, at least 16".
std::string sampling_words(const SampleBudget& samples);

// What differs between a stored identity (`whose`: "the checkpoint's") and this render's, in
// words ("seed: the checkpoint's '1', this render's '2'; ..."); empty when they agree.
std::string identity_mismatch(const RenderIdentity& stored, const RenderIdentity& now,
                              const std::string& whose);

// A digest of the fields every share of one render has (IdentityFieldDeclaration::shared):
// parts and ranks with the same digest add up to one render.
std::string shared_digest(const RenderIdentity& identity);

}  // namespace rtiow
