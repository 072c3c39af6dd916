#include "core/scene_file/scene_digest.h"

#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <type_traits>
#include <vector>

#include "core/io/checksum.h"
#include "core/scene_file/scene_file.h"
#include "materials/material.h"

namespace rtiow {
namespace {

// A value's bits, as the digest takes them (floats bit for bit, so -0 and 0 differ as in
// the scene's text).
template <typename T>
void add_bits(Checksum& c, const T& value) {
  if constexpr (std::is_same_v<T, Color>) {
    add_bits(c, value.x), add_bits(c, value.y), add_bits(c, value.z);  // not its padding
  } else {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    c.update(bytes, sizeof(T));
  }
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
  for (const Material& material : scene.materials) {
    visit_material(material, [&](const auto& m) {
      using M = std::decay_t<decltype(m)>;
      c.update(M::kType, std::strlen(M::kType) + 1);
      for_each_parameter<M>([&](const auto& d) { add_bits(c, m.*d.member); });
    });
  }
  const SphereSet& s = scene.spheres;
  add_array(c, s.center_x), add_array(c, s.center_y), add_array(c, s.center_z);
  add_array(c, s.radius), add_array(c, s.material);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016" PRIx64, c.value());
  return hex;
}

}  // namespace rtiow
