// libFuzzer target for the scene-file parser: any input must either load or be refused
// with InvalidInput. Any other exception, crash, leak or sanitizer report is a finding.

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/scene/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const rtiow::Scene scene =
        rtiow::parse_scene(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
    // A scene that loads must also write out and load again.
    rtiow::parse_scene(rtiow::scene_to_json(scene), "fuzz-rewritten.json");
  } catch (const rtiow::InvalidInput&) {
  }
  return 0;
}
