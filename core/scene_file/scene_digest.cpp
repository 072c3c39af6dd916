#include "core/scene_file/scene_digest.h"

#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "core/io/checksum.h"
#include "core/scene_file/scene_file.h"
#include "materials/material.h"

namespace rtiow {
namespace {

// A value's bits, as the digest takes them (floats bit for bit, so -0 and 0 differ as in
// the scene's text), appended to `bytes`.
template <typename T>
void append_bits(std::string& bytes, const T& value) {
  if constexpr (std::is_same_v<T, Color>) {
    append_bits(bytes, value.x), append_bits(bytes, value.y), append_bits(bytes, value.z);
  } else {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    bytes.append(raw, sizeof(T));
  }
}

template <typename T>
void add_bits(Checksum& c, const T& value) {
  std::string bytes;
  append_bits(bytes, value);
  c.update(bytes.data(), bytes.size());
}

template <typename T>
void add_array(Checksum& c, const std::vector<T>& values) {
  add_bits(c, std::uint64_t(values.size()));
  c.update(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

}  // namespace

// The scene's settings as its JSON text has them, and each material's type and declared
// parameters and the spheres' arrays as bits (formatting a million spheres' text to digest
// it took longer than reading them from a file).
std::string scene_digest(const Scene& scene) {
  static_assert(sizeof(SphereSet) == 5 * sizeof(std::vector<float>),
                "a sphere's new field belongs in the digest");
  Checksum c;
  const std::string settings = scene_settings_json(scene);
  c.update(settings.data(), settings.size());
  add_bits(c, std::uint64_t(scene.materials.size()));
  // Each material's bytes are gathered a block at a time: the checksum takes whole words
  // fastest, and a million materials fed a few bytes a call were most of the digest's time.
  constexpr std::size_t kBlockBytes = 16384;
  std::string block;
  block.reserve(kBlockBytes + 256);
  for (const Material& material : scene.materials) {
    visit_material(material, [&](const auto& m) {
      using M = std::decay_t<decltype(m)>;
      block.append(M::kType, std::strlen(M::kType) + 1);
      for_each_parameter<M>([&](const auto& d) { append_bits(block, m.*d.member); });
    });
    if (block.size() >= kBlockBytes) {
      c.update(block.data(), block.size());
      block.clear();
    }
  }
  c.update(block.data(), block.size());
  const SphereSet& s = scene.spheres;
  add_array(c, s.center_x), add_array(c, s.center_y), add_array(c, s.center_z);
  add_array(c, s.radius), add_array(c, s.material);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016" PRIx64, c.value());
  return hex;
}

}  // namespace rtiow
