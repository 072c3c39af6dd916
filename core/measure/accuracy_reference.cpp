#include "core/measure/accuracy_reference.h"
#include "core/limits/setting_name.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <system_error>
#include <variant>

#include "core/io/image_output.h"
#include "core/limits/error.h"
#include "core/render/render_identity.h"
#include "core/render/render_metadata.h"
#include "core/render/render_part.h"
#include "core/render/render_statistics.h"
#include "core/session/progress_display.h"

namespace rtiow {
namespace {

namespace fs = std::filesystem;

// The metadata key that ties a cached reference to its scene, settings and spp.
constexpr const char* kReferenceKey = "reference_key";

// A reference is a uniform render of a fixed count.
int reference_spp(const RenderSettings& settings) {
  return std::get<FixedSamples>(settings.samples).per_pixel;
}

std::string reference_key(const Scene& scene, const RenderSettings& settings) {
  return shared_digest(render_identity(scene, settings)) + "-" +
         std::to_string(reference_spp(settings)) + "spp";
}

}  // namespace

Reference load_or_render_reference(const Scene& scene, const RenderSettings& settings,
                                   const std::string& cache_dir, bool quiet, bool cache_dir_given) {
  const std::string key = reference_key(scene, settings);
  Reference reference;
  reference.path = (fs::path(cache_dir) / ("reference-" + key + ".exr")).string();
  // The cached reference, unless it is missing, unreadable or for other settings (then it is
  // rendered again and replaced).
  if (auto cached = read_statistics_image(reference.path, settings.width, settings.height,
                                          {{kReferenceKey, key}})) {
    reference.image = std::move(*cached);
    reference.reused = true;
    return reference;
  }
  // Where it will be kept, made and checked before minutes of rendering rather than after.
  std::error_code error;
  fs::create_directories(cache_dir, error);
  if (error || ::access(cache_dir.c_str(), W_OK | X_OK) != 0) {
    const int why = error ? error.value() : errno;
    // Named as the user gave it: an option, or the default they never typed.
    if (cache_dir_given) {
      throw InvalidInput(setting("cache_dir") + " " + quote_value(cache_dir) +
                         ": cannot keep the reference there: " + system_error_text(why));
    }
    throw InvalidInput("the default reference cache " + quote_value(cache_dir) +
                       " cannot keep the reference: " + system_error_text(why) + " (give " +
                       setting("cache_dir", "DIR") + " to keep it elsewhere)");
  }
  if (!quiet) {
    std::fprintf(stderr, "accuracy: rendering the reference (%dx%d, %d spp) into %s\n",
                 settings.width, settings.height, reference_spp(settings), reference.path.c_str());
  }
  RenderProgress progress;
  RenderResult result;
  {
    std::unique_ptr<ProgressDisplay> display;
    if (!quiet) {
      display = std::make_unique<ProgressDisplay>(progress, settings);
    }
    result = render(scene, settings, &progress);
  }
  namespace field = metadata_key;
  const Metadata metadata{{field::kScene, scene.name},
                          {field::kSpp, std::int64_t(reference_spp(settings))},
                          {field::kSeed, std::int64_t(settings.seed)},
                          {field::kDepth, std::int64_t(settings.max_depth)},
                          {field::kSampler, to_string(settings.sampler)},
                          {kReferenceKey, key}};
  write_image(reference.path, result.film, metadata, statistics_channels(result));
  reference.image = to_estimate(result);
  reference.render_seconds = result.render_seconds;
  return reference;
}

}  // namespace rtiow
