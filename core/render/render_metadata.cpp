#include "core/render/render_metadata.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/limits/number_text.h"
#include "core/render/render_outcome.h"
#include "core/render/render_statistics.h"

namespace rtiow {
namespace {

std::string triple(const Vec3d& v) {
  return shortest_text(v.x) + "," + shortest_text(v.y) + "," + shortest_text(v.z);
}

// A camera record's settings, in the scene file's words: each a vector or a number.
struct CameraSetting {
  const char* name;
  std::optional<Vec3d> CameraOverrides::*vector;
  std::optional<double> CameraOverrides::*number;
};
constexpr CameraSetting kCameraSettings[] = {
    {"lookfrom", &CameraOverrides::lookfrom, nullptr},
    {"lookat", &CameraOverrides::lookat, nullptr},
    {"vup", &CameraOverrides::vup, nullptr},
    {"vfov", nullptr, &CameraOverrides::vfov_degrees},
    {"aperture", nullptr, &CameraOverrides::aperture},
    {"focus_distance", nullptr, &CameraOverrides::focus_distance},
};

std::optional<double> read_number(std::string_view text) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

// "x,y,z" as a vector; nothing when it is not three numbers.
std::optional<Vec3d> read_triple(std::string_view text) {
  double v[3];
  for (int i = 0; i < 3; ++i) {
    const std::size_t comma = i < 2 ? text.find(',') : text.size();
    if (comma == std::string_view::npos) return std::nullopt;
    const std::optional<double> x = read_number(text.substr(0, comma));
    if (!x) return std::nullopt;
    v[i] = *x;
    text.remove_prefix(std::min(text.size(), comma + 1));
    if (i == 2 && comma != std::string_view::npos && !text.empty()) return std::nullopt;
  }
  return Vec3d{v[0], v[1], v[2]};
}

// A setting's name in a record of rtiow 0.3.0, which spelt it as the render command's option.
std::string name_of_older_record(std::string name) {
  if (name.rfind("--", 0) == 0) name.erase(0, 2);
  return name == "focus-dist" ? "focus_distance" : name;
}

// The reflectance models of the scene's glass ("schlick", "exact" or both), empty without glass.
std::string glass_reflectance(const Scene& scene) {
  bool schlick = false, exact = false;
  for (const Material& m : scene.materials) {
    if (const auto* d = std::get_if<Dielectric>(&m)) {
      (d->fresnel == FresnelModel::Exact ? exact : schlick) = true;
    }
  }
  return std::string(schlick ? "schlick" : "") + (schlick && exact ? "," : "") +
         (exact ? "exact" : "");
}

}  // namespace

std::string camera_record(const CameraSettings& c) {
  return "lookfrom " + triple(c.lookfrom) + " lookat " + triple(c.lookat) + " vup " +
         triple(c.vup) + " vfov " + shortest_text(c.vfov_degrees) + " aperture " +
         shortest_text(c.aperture) + " focus_distance " + shortest_text(focus_distance_of(c));
}

CameraOverrides read_camera_record(const std::string& record, const std::string& source) {
  CameraOverrides camera;
  std::istringstream words(record);
  std::string name, value;
  const auto refuse = [&](const std::string& why) {
    throw InvalidInput(source + ": " + kMetadataPrefix + metadata_key::kCamera + ": " + why);
  };
  while (words >> name) {
    if (!(words >> value)) refuse(quote_value(name) + " has no value");
    const std::string setting = name_of_older_record(name);
    const CameraSetting* known = nullptr;
    for (const CameraSetting& c : kCameraSettings) {
      if (setting == c.name) known = &c;
    }
    if (!known) refuse("unknown setting " + quote_value(name));
    if (known->vector) {
      if (camera.*known->vector) refuse(quote_value(name) + " is given twice");
      camera.*known->vector = read_triple(value);
      if (!(camera.*known->vector)) refuse(quote_value(name) + " is not x,y,z");
    } else {
      if (camera.*known->number) refuse(quote_value(name) + " is given twice");
      camera.*known->number = read_number(value);
      if (!(camera.*known->number)) refuse(quote_value(name) + " is not a number");
    }
  }
  return camera;  // what it leaves out is the scene's
}

namespace {

// An adaptive render's sampling: its target or budget, and the range and mean of its pixels'
// counts (each pixel has its own count: not one "spp").
void add_adaptive_sampling(const RenderSettings& s, const RenderResult& r,
                           const RenderOutcome& outcome, Metadata& metadata) {
  namespace key = metadata_key;
  // Each pixel has its own count: the range and the mean, not one "spp".
  std::uint32_t limit = limits::kMostAdaptiveSamples;
  if (const auto* t = std::get_if<PixelErrorTarget>(&s.samples)) {
    metadata.emplace_back(key::kTargetError, t->error);
    metadata.emplace_back(key::kPixelsAboveTarget, std::int64_t(r.pixels_above_target));
    limit = std::uint32_t(t->most);
  }
  if (const auto* i = std::get_if<ImageErrorTarget>(&s.samples)) {
    metadata.emplace_back(key::kImageError, i->error);
    metadata.emplace_back(key::kEstimatedImageError, r.estimated_image_error);
    limit = std::uint32_t(i->most);
  }
  if (const auto* a = std::get_if<AdaptiveBudget>(&s.samples)) {
    metadata.emplace_back(key::kAdaptive, std::string("sqrt(variance/cost)"));
    if (a->per_pixel) {  // else the time limit's
      metadata.emplace_back(key::kSppBudget, std::int64_t(*a->per_pixel));
    }
  }
  metadata.insert(metadata.end(),
                  {
                      {key::kMinSpp, std::int64_t(least_samples(s.samples).value_or(0))},
                      {key::kSppMin, std::int64_t(outcome.least)},
                      {key::kSppMax, std::int64_t(outcome.most)},
                      {key::kSppMean, outcome.mean},
                      {key::kSppLimit, std::int64_t(limit)},
                  });
}

}  // namespace

Metadata render_metadata(const Scene& scene, const RenderSettings& s, const RenderResult& r,
                         bool reproducible) {
  namespace key = metadata_key;
  using F = IdentityField;
  const RenderIdentity identity = render_identity(scene, s);
  Metadata metadata{{key::kScene, scene.name},
                    identity_metadata(identity, F::Scene),
                    {key::kCamera, camera_record(scene.camera)},
                    identity_metadata(identity, F::Version)};
  if (const std::string fresnel = glass_reflectance(scene); !fresnel.empty())
    metadata.emplace_back(key::kFresnel, fresnel);
  if (scene.layout_seed) metadata.emplace_back(key::kSceneSeed, whole_metadata(*scene.layout_seed));
  if (s.crop) {
    metadata.emplace_back(key::kCrop, to_string(*s.crop));
    metadata.emplace_back(key::kFrame, std::to_string(s.width) + "x" + std::to_string(s.height));
  }
  if (s.passes.any()) metadata.emplace_back(key::kPasses, to_string(s.passes));
  for (const F field : {F::Depth, F::Seed, F::Sampler, F::Replicates, F::Roulette}) {
    metadata.push_back(identity_metadata(identity, field));
  }
  metadata.insert(metadata.end(), {{key::kAccelerator, to_string(s.accel)},
                                   {key::kRaysTraced, std::int64_t(r.rays_traced)}});
  const RenderOutcome outcome = describe_outcome(s, r);
  if (is_adaptive(s)) {
    add_adaptive_sampling(s, r, outcome, metadata);
  } else {
    metadata.emplace_back(key::kSpp, std::int64_t(r.samples_completed));
  }
  if (r.error_estimate != ErrorEstimate::None) {
    if (!std::holds_alternative<ImageErrorTarget>(s.samples)) {
      metadata.emplace_back(key::kEstimatedImageError, r.estimated_image_error);
    }
    metadata.emplace_back(key::kErrorEstimate, to_string(r.error_estimate));
  }
  if (const auto* fixed = std::get_if<FixedSamples>(&s.samples); fixed && r.stopped) {
    metadata.emplace_back(key::kSppRequested, std::int64_t(fixed->per_pixel));
  }
  if (!outcome.stopped.empty()) metadata.emplace_back(key::kStopped, outcome.stopped);
  if (!reproducible) metadata.emplace_back(key::kRenderSeconds, r.render_seconds);
  return metadata;
}

namespace {

// Whole numbers separated by `separator`, exactly `count` of them, each within [0, limit].
std::optional<std::vector<int>> numbers(const std::string& text, char separator, std::size_t count,
                                        int limit) {
  std::vector<int> values;
  const char* at = text.data();
  const char* end = text.data() + text.size();
  while (values.size() < count) {
    int value = 0;
    const auto [next, error] = std::from_chars(at, end, value);
    if (error != std::errc() || value < 0 || value > limit) return std::nullopt;
    values.push_back(value);
    at = next;
    if (values.size() < count) {
      if (at == end || *at != separator) return std::nullopt;
      ++at;
    }
  }
  if (at != end) return std::nullopt;
  return values;
}

}  // namespace

FramePlacement recorded_placement(const Metadata& metadata, const std::string& source, int width,
                                  int height) {
  const std::string* crop = nullptr;
  const std::string* frame = nullptr;
  for (const auto& [key, value] : metadata) {
    if (key == metadata_key::kCrop) crop = std::get_if<std::string>(&value);
    if (key == metadata_key::kFrame) frame = std::get_if<std::string>(&value);
  }
  if (!crop && !frame) return {};
  const auto region =
      crop ? numbers(*crop, ',', 4, limits::kMaxImageSide) : std::optional<std::vector<int>>();
  const auto size =
      frame ? numbers(*frame, 'x', 2, limits::kMaxImageSide) : std::optional<std::vector<int>>();
  if (!region || !size || (*region)[0] >= (*region)[2] || (*region)[1] >= (*region)[3] ||
      (*region)[2] > (*size)[0] || (*region)[3] > (*size)[1]) {
    throw InvalidInput(source + ": " + kMetadataPrefix + metadata_key::kCrop + " " +
                       quote_value(crop ? *crop : "") + " and " + kMetadataPrefix +
                       metadata_key::kFrame + " " + quote_value(frame ? *frame : "") +
                       " are not a region of a frame");
  }
  if ((*region)[2] - (*region)[0] != width || (*region)[3] - (*region)[1] != height) {
    throw InvalidInput(source + ": " + kMetadataPrefix + metadata_key::kCrop + " " +
                       quote_value(*crop) + " is not the " + std::to_string(width) + "x" +
                       std::to_string(height) + " image's region");
  }
  return {(*region)[0], (*region)[1], (*size)[0], (*size)[1]};
}

}  // namespace rtiow
