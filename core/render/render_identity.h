#pragma once
// Which render this is: what must agree for a checkpoint to continue a render, for shares
// (part files, MPI ranks) to add up to one, and for a cached reference to stand for another.
// Declared once, in the library's own words: the checkpoint's header keys, the part files'
// digest and every "what differs" message follow this table, so a file format never depends
// on how a front end spells its options.

#include <array>
#include <cstddef>
#include <string>

#include "core/io/image_output.h"
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
  // In an image's metadata ("rtiow:<key>", core/render/render_metadata.h), where one key holds
  // it: that key, and whether it is written as a whole number. Null where the metadata says it
  // in other words: the size as the image's own with its crop and frame, the sampling as its
  // mode and where it ended, the passes as their list, a share's first sample in a part's own
  // fields.
  const char* metadata_key;
  bool whole_number;
};

inline constexpr std::array<IdentityFieldDeclaration, 11> kIdentityFields = {{
    // merge names the version first
    {IdentityField::Version, "version", "rtiow version", false, "version", false},
    {IdentityField::Scene, "scene", "scene", true, "scene_digest", false},
    {IdentityField::Size, "size", "image size", true, nullptr, false},
    {IdentityField::Depth, "depth", "depth", true, "depth", true},
    {IdentityField::Seed, "seed", "seed", true, "seed", true},
    {IdentityField::Sampler, "sampler", "sampler", true, "sampler", false},
    {IdentityField::Replicates, "replicates", "replicates", true, "replicates", true},
    {IdentityField::Roulette, "roulette", "Russian roulette", true, "russian_roulette", false},
    {IdentityField::FirstSample, "first_sample", "first sample", false, nullptr, false},
    {IdentityField::Sampling, "sampling", "sampling", false, nullptr, false},
    {IdentityField::Passes, "passes", "passes", false, nullptr, false},
}};

constexpr const IdentityFieldDeclaration& declaration_of(IdentityField f) {
  return kIdentityFields[std::size_t(f)];
}

// The table is in the enum's order, so declaration_of() is an index.
constexpr bool declared_in_order() {
  for (std::size_t i = 0; i < kIdentityFields.size(); ++i) {
    if (std::size_t(kIdentityFields[i].field) != i) return false;
  }
  return true;
}
static_assert(declared_in_order());

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

// `field` as an image's metadata records it: its declaration's metadata key, with the value as
// text, or as a whole number where declared so (as its digits where a whole number's 64 bits
// cannot hold it: a seed above 2^63 - 1). `field` must have a metadata key.
std::pair<std::string, MetadataValue> identity_metadata(const RenderIdentity& identity,
                                                        IdentityField field);

// A digest of the fields every share of one render has (IdentityFieldDeclaration::shared):
// parts and ranks with the same digest add up to one render.
std::string shared_digest(const RenderIdentity& identity);

}  // namespace rtiow
