#include "app/accuracy_reference.h"

#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "app/progress_display.h"
#include "core/film/render_statistics.h"
#include "core/io/error.h"
#include "core/io/image_output.h"
#include "core/render/render_part.h"

namespace rtiow {
namespace {

namespace fs = std::filesystem;

constexpr int kChannels = 7;  // R, G, B, spp, variance.R, variance.G, variance.B

std::string reference_key(const Scene& scene, const RenderSettings& settings) {
  return render_digest(scene, settings) + "-" + std::to_string(settings.samples_per_pixel) + "spp";
}

// The cached reference, or nothing when the file is missing, unreadable or for other
// settings (then it is rendered again and replaced).
std::optional<ImageEstimate> read_reference(const std::string& path, const std::string& key,
                                            const RenderSettings& settings) {
  if (!fs::exists(path)) return std::nullopt;
  auto in = OIIO::ImageInput::open(path);
  if (!in) return std::nullopt;
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width != settings.width || spec.height != settings.height ||
      spec.nchannels != kChannels || spec.get_string_attribute("rtiow:reference_key") != key) {
    return std::nullopt;
  }
  std::vector<float> values(std::size_t(spec.width) * std::size_t(spec.height) * kChannels);
  if (!in->read_image(0, 0, 0, kChannels, OIIO::TypeDesc::FLOAT, values.data())) {
    return std::nullopt;
  }
  ImageEstimate image{Film(spec.width, spec.height), {}};
  for (std::size_t p = 0; p < image.film.pixels().size(); ++p) {
    const float* v = &values[p * kChannels];
    image.film.at(int(p % std::size_t(spec.width)), int(p / std::size_t(spec.width))) = {v[0], v[1],
                                                                                         v[2]};
    image.variance.push_back({v[4], v[5], v[6]});
  }
  return image;
}

}  // namespace

Reference load_or_render_reference(const Scene& scene, const RenderSettings& settings,
                                   const std::string& cache_dir, bool quiet) {
  const std::string key = reference_key(scene, settings);
  Reference reference;
  reference.path = (fs::path(cache_dir) / ("reference-" + key + ".exr")).string();
  if (auto cached = read_reference(reference.path, key, settings)) {
    reference.image = std::move(*cached);
    reference.reused = true;
    return reference;
  }
  if (!quiet) {
    std::fprintf(stderr, "accuracy: rendering the reference (%dx%d, %d spp) into %s\n",
                 settings.width, settings.height, settings.samples_per_pixel,
                 reference.path.c_str());
  }
  RenderProgress progress;
  RenderResult result;
  {
    std::unique_ptr<ProgressDisplay> display;
    if (!quiet) {
      display = std::make_unique<ProgressDisplay>(
          progress, std::uint64_t(settings.width) * std::uint64_t(settings.height) *
                        std::uint64_t(settings.samples_per_pixel));
    }
    result = render(scene, settings, &progress);
  }
  fs::create_directories(cache_dir);
  const Metadata metadata{{"scene", scene.name},
                          {"spp", std::int64_t(settings.samples_per_pixel)},
                          {"seed", std::int64_t(settings.seed)},
                          {"depth", std::int64_t(settings.max_depth)},
                          {"sampler", to_string(settings.sampler)},
                          {"reference_key", key}};
  write_image(reference.path, result.film, metadata, statistics_channels(result));
  reference.image = to_estimate(result);
  reference.render_seconds = result.render_seconds;
  return reference;
}

}  // namespace rtiow
