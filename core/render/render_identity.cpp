#include "core/render/render_identity.h"

#include <charconv>
#include <cstdio>
#include <stdexcept>
#include <variant>

#include "core/limits/error.h"
#include "core/limits/number_text.h"
#include "core/sampling/rng.h"
#include "core/scene_file/scene_digest.h"
#include "core/version.h"

namespace rtiow {
namespace {

std::string range(int least, int most) {
  return std::to_string(least) + " to " + std::to_string(most) + " samples";
}

}  // namespace

std::string sampling_words(const SampleBudget& samples) {
  if (const auto* t = std::get_if<PixelErrorTarget>(&samples)) {
    return "pixel error " + shortest_text(t->error) + ", " + range(t->least, t->most);
  }
  if (const auto* i = std::get_if<ImageErrorTarget>(&samples)) {
    return "image error " + shortest_text(i->error) + (i->denoised ? " denoised" : "") + ", " +
           range(i->least, i->most);
  }
  if (const auto* a = std::get_if<AdaptiveBudget>(&samples)) {
    return "adaptive, " +
           (a->per_pixel ? std::to_string(*a->per_pixel) + " samples a pixel"
                         : std::string("within the time limit")) +
           ", at least " + std::to_string(a->least);
  }
  return "uniform";  // a uniform render continues to any count
}

RenderIdentity render_identity(const Scene& scene, const RenderSettings& s) {
  RenderIdentity id;
  using F = IdentityField;
  id[F::Version] = version();
  id[F::Scene] = scene_digest(scene);
  id[F::Size] = std::to_string(s.width) + "x" + std::to_string(s.height) +
                (s.crop ? " crop " + to_string(*s.crop) : "");
  id[F::Depth] = std::to_string(s.max_depth);
  id[F::Seed] = std::to_string(s.seed);
  id[F::Sampler] = to_string(s.sampler);
  id[F::Replicates] = std::to_string(replicates(s));
  id[F::Roulette] = roulette_name(s.russian_roulette);
  id[F::FirstSample] = std::to_string(s.first_sample);
  id[F::Sampling] = sampling_words(s.samples);
  id[F::Passes] = s.passes.any() ? "albedo, normal and depth kept" : "none";
  return id;
}

std::string identity_mismatch(const RenderIdentity& stored, const RenderIdentity& now,
                              const std::string& whose) {
  std::string text;
  for (const IdentityFieldDeclaration& d : kIdentityFields) {
    const std::string& a = stored[d.field];
    const std::string& b = now[d.field];
    if (a == b) continue;
    if (!text.empty()) text += "; ";
    text += std::string(d.label) + ": " + whose + " " + quote_value(a, 60) + ", this render's " +
            quote_value(b, 60);
  }
  return text;
}

std::pair<std::string, MetadataValue> identity_metadata(const RenderIdentity& identity,
                                                        IdentityField field) {
  const IdentityFieldDeclaration& d = declaration_of(field);
  if (!d.metadata_key) throw std::logic_error(std::string(d.key) + " has no metadata key");
  const std::string& text = identity[field];
  if (!d.whole_number) return {d.metadata_key, text};
  std::uint64_t bits = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), bits);
  if (error != std::errc() || end != text.data() + text.size()) {
    throw std::logic_error(std::string(d.key) + " is not a whole number: " + text);
  }
  return {d.metadata_key, whole_metadata(bits)};
}

std::string shared_digest(const RenderIdentity& identity) {
  std::uint64_t h = 0x6a09e667f3bcc908ull;
  for (const IdentityFieldDeclaration& d : kIdentityFields) {
    if (!d.shared) continue;
    for (const char* c = d.key; *c; ++c) h = hash_combine(h, std::uint8_t(*c));
    h = hash_combine(h, '=');
    for (const unsigned char c : identity[d.field]) h = hash_combine(h, c);
    h = hash_combine(h, '|');
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

}  // namespace rtiow
