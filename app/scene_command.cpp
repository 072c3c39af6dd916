#include "app/scene_command.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/io/atomic_file.h"
#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/scene/builtin_scenes.h"
#include "core/scene_file/scene_file.h"

namespace rtiow {

int run_scene(const SceneOptions& o) {
  if (o.output_given && o.output.empty()) throw InvalidInput("-o/--output: the path is empty");
  const bool to_stdout = o.output.empty() || o.output == "-";
  if (!to_stdout) check_output_path(o.output, {});
  // `rtiow scene cover -o c.png` would write JSON under an image's name.
  if (!to_stdout && image_format(o.output) != nullptr) {
    throw InvalidInput("-o " + quote_value(o.output) +
                       ": a scene is JSON, not an image; name it .json (an image of it: rtiow "
                       "render --scene " +
                       o.name + " -o " + o.output + ")");
  }
  std::optional<OutputClaim> claim;  // held from before the scene is made
  if (!to_stdout) claim.emplace(o.output);
  const std::string text = scene_to_json(make_builtin_scene(o.name, o.scene_seed));
  if (to_stdout) {
    std::fwrite(text.data(), 1, text.size(), stdout);
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
      throw std::runtime_error(std::string("cannot write to standard output: ") +
                               std::strerror(errno));
    }
    return 0;
  }
  write_text_atomically(o.output, text);
  return 0;
}

}  // namespace rtiow
