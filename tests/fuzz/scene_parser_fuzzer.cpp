// libFuzzer target for the scene-file parser: any input must either load or be refused
// with InvalidInput. Any other exception, crash, leak or sanitizer report is a finding. The
// parse in runs that big files take (read_scene_in_runs) must agree with it: the same scene
// where it loads, nothing where it is refused.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>

#include "core/scene_file/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::optional<rtiow::Scene> whole;
  try {
    whole = rtiow::parse_scene(text, "fuzz.json");
    // A scene that loads must also write out and load again.
    rtiow::parse_scene(rtiow::scene_to_json(*whole), "fuzz-rewritten.json");
  } catch (const rtiow::InvalidInput&) {
  }
  // Windows and runs as small as the input's first bytes say, so the cuts fall everywhere.
  const std::size_t window = 1 + (size > 0 ? data[0] % 97 : 0);
  const std::size_t run = 1 + (size > 1 ? data[1] % 61 : 0);
  std::size_t offset = 0;
  const std::optional<rtiow::Scene> split = rtiow::read_scene_in_runs(
      [&](char* buffer, std::size_t n) {
        n = std::min(n, text.size() - offset);
        std::memcpy(buffer, text.data() + offset, n);
        offset += n;
        return n;
      },
      "fuzz.json", run, window);
  // Members or a skeleton over 1 MiB are left to the one-piece parse; no input here is that big.
  if (split.has_value() != whole.has_value()) __builtin_trap();
  if (whole && (rtiow::scene_to_json(*split) != rtiow::scene_to_json(*whole) ||
                split->spheres.material != whole->spheres.material)) {
    __builtin_trap();
  }
  return 0;
}
