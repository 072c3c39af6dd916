#include "core/render/recorded_request.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>

#include "core/io/image_backend.h"
#include "core/io/image_file.h"
#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/limits/number_text.h"
#include "core/limits/setting_name.h"
#include "core/render/render_metadata.h"
#include "core/scene_file/json_stream.h"
#include "core/scene_file/scene_digest.h"

namespace rtiow {
namespace {

using Recorded = std::map<std::string, std::string>;  // key (without "rtiow:") -> text

// The rtiow:* keys of a JSON object in an image's description, read by the reader every JSON
// input goes through (bounded, no duplicate keys). A description that is not JSON (another
// program's text) holds none; one that holds rtiow keys but does not read is refused by name
// (`source`: its description, where and why).
void add_json_keys(const std::string& description, const std::string& source, Recorded& recorded) {
  JsonDocument all;
  const std::string where = source + ": its description";
  try {
    JsonInput input(JsonInput::from_text(description), description.size(), where);
    parse_json_stream(input, where, {}, all);
  } catch (const InvalidInput&) {
    if (description.find(std::string("\"") + kMetadataPrefix) == std::string::npos) return;
    throw;
  }
  if (!all.IsObject()) return;
  const std::string_view prefix = kMetadataPrefix;
  for (const JsonMember& m : members(all)) {
    const std::string_view name = text_of(m.name);
    if (!name.starts_with(prefix)) continue;
    const std::string key(name.substr(prefix.size()));
    if (m.value.IsString()) {
      recorded[key] = std::string(text_of(m.value));
    } else if (m.value.IsInt64()) {
      recorded[key] = std::to_string(m.value.GetInt64());
    } else if (m.value.IsUint64()) {
      recorded[key] = std::to_string(m.value.GetUint64());
    } else if (m.value.IsNumber()) {
      recorded[key] = shortest_text(m.value.GetDouble());
    }
  }
}

// Every rtiow:* key of the header: its own attributes (PNG, EXR), or the JSON object in the
// image description (JPEG, TIFF).
Recorded recorded_keys(const ImageHeader& header, const std::string& source) {
  Recorded recorded;
  const std::string prefix = kMetadataPrefix;
  for (const ImageAttribute& a : header.attributes) {
    if (a.name == "ImageDescription") {
      if (const auto* text = std::get_if<std::string>(&a.value))
        add_json_keys(*text, source, recorded);
      continue;
    }
    if (a.name.rfind(prefix, 0) != 0) continue;
    const std::string key = a.name.substr(prefix.size());
    if (const auto* i = std::get_if<int>(&a.value)) recorded[key] = std::to_string(*i);
    if (const auto* f = std::get_if<float>(&a.value))
      recorded[key] = shortest_text(*f);  // EXR keeps doubles as floats
    if (const auto* s = std::get_if<std::string>(&a.value)) recorded[key] = *s;
  }
  return recorded;
}

// The recorded keys, each read as what it must be, refused by name where it is not.
class KeyReader {
 public:
  KeyReader(const std::string& source, Recorded recorded)
      : source_(source), recorded_(std::move(recorded)) {}

  bool empty() const { return recorded_.empty(); }
  const std::string* find(const char* key) const {
    const auto it = recorded_.find(key);
    return it == recorded_.end() ? nullptr : &it->second;
  }
  const std::string& need(const char* key) const {
    if (const std::string* value = find(key)) return *value;
    throw InvalidInput(source_ + " has no " + kMetadataPrefix + key +
                       ": it was written before rtiow recorded the whole request, or its "
                       "metadata was edited since");
  }
  [[noreturn]] void refuse(const std::string& why) const {
    throw InvalidInput(source_ + ": " + why);
  }
  [[noreturn]] void refuse(const char* key, const std::string& why) const {
    refuse(std::string(kMetadataPrefix) + key + " " + quote_value(need(key), 40) + " " + why);
  }
  template <typename T>
  T whole(const char* key, T least, T most) const {
    const std::string& text = need(key);
    T value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || value < least || value > most) {
      refuse(key,
             "is not a whole number from " + std::to_string(least) + " to " + std::to_string(most));
    }
    return value;
  }
  int count(const char* key) const { return whole<int>(key, 1, std::numeric_limits<int>::max()); }
  double fraction(const char* key) const {  // a relative error
    const std::string& text = need(key);
    double value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || !(value > 0.0) ||
        !(value < 1.0)) {
      refuse(key, "is not a relative error between 0 and 1");
    }
    return value;
  }
  template <typename Parse>
  auto parsed(const char* key, Parse parse) const {
    try {
      return parse(need(key));
    } catch (const InvalidInput& e) {
      refuse(key, std::string("is not one rtiow takes: ") + e.what());
    }
  }

 private:
  std::string source_;
  Recorded recorded_;
};

// How many samples, and how they were spent: the count of a uniform render (also where a
// signal or a time limit stopped it early), or the adaptive mode with its cap and minimum.
void read_samples(const KeyReader& keys, RecordedRequest& out) {
  namespace key = metadata_key;
  RenderRequest& r = out.job.request;
  const std::string give =
      "; give the sampling (" + setting("spp") + ", " + setting("target_error") + ", ...)";
  if (keys.find(key::kSpp)) {
    r.spp = keys.count(key::kSpp);
    return;
  }
  if (const std::string* stopped = keys.find(key::kStopped)) {
    out.unrepeatable[RequestPart::Samples] = "its adaptive render was stopped early (" +
                                             quote_value(*stopped) +
                                             "): where each pixel stopped depends on when" + give;
    return;
  }
  if (keys.find(key::kTargetError)) {
    r.target_error = keys.fraction(key::kTargetError);
    r.spp = keys.count(key::kSppLimit);
  } else if (keys.find(key::kImageError)) {
    r.image_error = keys.fraction(key::kImageError);
    r.spp = keys.count(key::kSppLimit);
  } else if (keys.find(key::kAdaptive)) {
    if (!keys.find(key::kSppBudget)) {
      out.unrepeatable[RequestPart::Samples] =
          "its adaptive budget was a time limit, which gives another image on another machine" +
          give;
      return;
    }
    r.adaptive = true;
    r.spp = keys.count(key::kSppBudget);
  } else {
    keys.need(key::kSpp);  // refused: no sampling recorded
  }
  if (keys.find(key::kMinSpp)) r.min_samples = keys.count(key::kMinSpp);
}

// The image's size, or for a crop the frame's size and the region.
void read_size(const KeyReader& keys, const ImageHeader& header, RecordedRequest& out) {
  namespace key = metadata_key;
  RenderRequest& r = out.job.request;
  const std::string* crop = keys.find(key::kCrop);
  const std::string* frame = keys.find(key::kFrame);
  if (!crop && !frame) {
    r.width = header.width, r.height = header.height;
    return;
  }
  const Metadata recorded{{key::kCrop, crop ? *crop : std::string()},
                          {key::kFrame, frame ? *frame : std::string()}};
  const FramePlacement place =
      recorded_placement(recorded, out.source, header.width, header.height);
  r.width = place.frame_width, r.height = place.frame_height;
  r.crop = PixelRegion{place.x, place.y, place.x + header.width, place.y + header.height};
}

// The scene: a file, or a built-in scene and its layout.
void read_scene(const KeyReader& keys, JobRequest& job) {
  namespace key = metadata_key;
  if (const std::string* file = keys.find(key::kSceneFile)) {
    job.scene_file = *file;
    return;
  }
  job.scene = keys.need(key::kScene);
  if (keys.find(key::kSceneSeed)) {
    job.scene_seed =
        keys.whole<std::uint64_t>(key::kSceneSeed, 0, std::numeric_limits<std::uint64_t>::max());
  }
}

// What the image holds beside its colour: the statistics channels, and the passes.
void read_channels(const KeyReader& keys, const ImageHeader& header, JobRequest& job) {
  namespace key = metadata_key;
  RenderRequest& r = job.request;
  // The statistics channels, or two replicates in a uniform render or on an adaptive budget
  // (the error targets keep two whatever was asked) of a sampler whose one sequence differs
  // from two replicates (independent samples are the same either way): they were asked for.
  const std::string* replicates = keys.find(key::kReplicates);
  const auto& channels = header.channel_names;
  const bool asked_replicates = replicates && *replicates == "2" &&
                                r.sampler != SamplerKind::Independent &&
                                (keys.find(key::kSpp) || keys.find(key::kAdaptive));
  // A denoised image keeps two replicates for the denoiser, not because they were asked.
  job.denoise = keys.find(key::kDenoisedError) != nullptr;
  job.stats_channels = r.estimate_error =
      std::find(channels.begin(), channels.end(), "variance.R") != channels.end() ||
      (asked_replicates && !job.denoise);
  if (keys.find(key::kPasses)) {
    r.passes = keys.parsed(key::kPasses, [](const std::string& list) {
      try {
        return parse_passes(list);
      } catch (const InvalidInput&) {
        throw InvalidInput("a list of passes is some of " + pass_names());
      }
    });
  }
}

RecordedRequest recorded_request(const ImageHeader& header, const std::string& source) {
  namespace key = metadata_key;
  const KeyReader keys(source, recorded_keys(header, source));
  if (keys.empty()) {
    keys.refuse(
        "holds no rtiow provenance (HDR, PPM, BMP and TGA keep none; PNG, EXR, JPEG and TIFF "
        "do)");
  }
  if (keys.find("part_samples")) {
    keys.refuse(
        "is a part of a shared render: merge the parts (rtiow merge) and use the merged "
        "image");
  }
  RecordedRequest out;
  out.source = source;
  out.scene_digest = keys.need(key::kSceneDigest);
  out.version = keys.need(key::kVersion);
  JobRequest& job = out.job;
  RenderRequest& r = job.request;
  read_scene(keys, job);
  read_size(keys, header, out);
  read_samples(keys, out);
  r.max_depth = keys.whole<int>(key::kDepth, 0, std::numeric_limits<int>::max());
  r.seed = keys.whole<std::uint64_t>(key::kSeed, 0, std::numeric_limits<std::uint64_t>::max());
  r.sampler = keys.parsed(key::kSampler, parse_sampler);
  if (keys.find(key::kAccelerator)) r.accel = keys.parsed(key::kAccelerator, parse_accel);
  if (const std::string* roulette = keys.find(key::kRussianRoulette)) {  // absent: on
    if (*roulette != roulette_name(true) && *roulette != roulette_name(false)) {
      keys.refuse(key::kRussianRoulette, "is neither on nor off");
    }
    r.russian_roulette = *roulette == roulette_name(true);
  }
  r.camera = read_camera_record(keys.need(key::kCamera), source);
  // One model for all the glass, as the override gave it or the scene said; a scene that mixes
  // the two gives both names, and its own glass says which.
  if (const std::string* fresnel = keys.find(key::kFresnel)) r.fresnel = parse_fresnel(*fresnel);
  read_channels(keys, header, job);
  out.reproducible = !keys.find(key::kRenderSeconds);
  return out;
}

// The image records its scene file as it was given, relative to where that render ran: from
// elsewhere it names no file, and the caller is told where the name came from.
void check_recorded_scene_file(const RecordedRequest& image) {
  const std::string& file = image.job.scene_file;
  std::error_code error;
  if (file.empty() || std::filesystem::exists(file, error)) return;
  const bool relative = std::filesystem::path(file).is_relative();
  throw InvalidInput(image.source + " was rendered from scene file " + quote_value(file) +
                     (relative ? ", a name relative to the directory that render ran in; " : ", ") +
                     "there is no such file from here: give the scene file");
}

}  // namespace

RecordedRequest read_recorded_request(const std::string& path, const std::string& source) {
  const auto in = open_input_image(path, source, limits::kMaxPartFileBytes, "image");
  return recorded_request(in->header(), source);
}

JobRequest overlay_recorded(const RecordedRequest& image, JobRequest asked,
                            const std::set<RequestPart>& given, bool output_holds_channels,
                            bool& reproducible) {
  using P = RequestPart;
  const auto left = [&](P part) { return given.count(part) == 0; };
  const RenderRequest& i = image.job.request;
  RenderRequest& r = asked.request;
  // A new frame would drop the image's region without a word.
  if (i.crop && !left(P::Size) && left(P::Crop)) {
    const PixelRegion& c = *i.crop;
    throw InvalidInput(
        image.source + " is the region " + to_string(c) + " of its frame; " + setting("width") +
        " or " + setting("height") + " makes another frame, whose region it cannot know: give " +
        setting("crop") + " too (" + setting("crop", "0,0,W,H") + " for the whole frame)");
  }
  if (left(P::Scene) && left(P::SceneSeed)) check_recorded_scene_file(image);
  for (const auto& [part, why] : image.unrepeatable) {
    if (left(part)) throw InvalidInput(image.source + ": " + why);
  }
  if (left(P::Scene)) asked.scene_file = image.job.scene_file, asked.scene = image.job.scene;
  if (left(P::SceneSeed)) asked.scene_seed = image.job.scene_seed;
  if (left(P::Size)) r.width = i.width, r.height = i.height;
  if (left(P::Size) && left(P::Crop)) r.crop = i.crop;
  if (left(P::Samples)) {
    r.spp = i.spp, r.target_error = i.target_error, r.image_error = i.image_error;
    r.adaptive = i.adaptive, r.min_samples = i.min_samples;
    r.time_limit_seconds = i.time_limit_seconds;
  }
  if (left(P::Depth)) r.max_depth = i.max_depth;
  if (left(P::Seed)) r.seed = i.seed;
  if (left(P::Sampler)) r.sampler = i.sampler;
  if (left(P::Accelerator)) r.accel = i.accel;
  if (left(P::Roulette)) r.russian_roulette = i.russian_roulette;
  CameraOverrides& c = r.camera;
  if (left(P::Lookfrom) && i.camera.lookfrom) c.lookfrom = i.camera.lookfrom;
  if (left(P::Lookat) && i.camera.lookat) c.lookat = i.camera.lookat;
  if (left(P::Vup) && i.camera.vup) c.vup = i.camera.vup;
  if (left(P::Vfov) && i.camera.vfov_degrees) c.vfov_degrees = i.camera.vfov_degrees;
  if (left(P::Aperture) && i.camera.aperture) c.aperture = i.camera.aperture;
  if (left(P::FocusDistance) && i.camera.focus_distance) {
    c.focus_distance = i.camera.focus_distance;
  }
  if (left(P::Fresnel) && i.fresnel) r.fresnel = i.fresnel;
  if (left(P::StatsChannels) && image.job.stats_channels) {
    // Two replicates give other pixels than one sequence, and only an output with room for
    // the channels that come with them renders the image's pixels again.
    if (!output_holds_channels) {
      throw InvalidInput(image.source +
                         " was rendered with the statistics channels, whose two replicates give "
                         "other pixels than one sequence: render it again into an .exr (" +
                         setting("output", "NAME.exr") + ")");
    }
    asked.stats_channels = r.estimate_error = true;
  }
  if (left(P::Denoise) && image.job.denoise) asked.denoise = true;  // it asks for the passes
  if (left(P::Passes) && i.passes.any() && output_holds_channels && !asked.denoise)
    r.passes = i.passes;
  if (left(P::Reproducible) && image.reproducible) reproducible = true;
  return asked;
}

void check_scene_of_image(const RecordedRequest& image, const Scene& scene) {
  RenderRequest as_recorded;
  as_recorded.camera = image.job.request.camera;
  as_recorded.fresnel = image.job.request.fresnel;
  const std::string digest = scene_digest(resolve(scene, as_recorded).scene);
  if (digest == image.scene_digest) return;
  const std::string which =
      image.job.scene_file.empty()
          ? "built-in scene " + quote_value(scene.name) + " is not the one rtiow " +
                quote_value(image.version) + " rendered it from"
          : "scene file " + quote_value(image.job.scene_file) +
                " is not the scene it was rendered from; the file changed since";
  throw InvalidInput(image.source + ": " + which + " (digest " + image.scene_digest + " then, " +
                     digest + " now); give the scene (a file or " + setting("scene") +
                     ") to render it anyway");
}

namespace {

// The settings that give each part.
const std::vector<std::pair<RequestPart, std::vector<std::string_view>>>& part_settings() {
  using P = RequestPart;
  static const std::vector<std::pair<P, std::vector<std::string_view>>> table = {
      {P::Scene, {"scene_file", "scene"}},
      {P::SceneSeed, {"scene_seed", "scene_file"}},  // a layout goes with a built-in scene
      {P::Size, {"width", "height"}},
      {P::Crop, {"crop"}},
      {P::Samples, {"spp", "target_error", "image_error", "adaptive", "min_spp", "time_limit"}},
      {P::Depth, {"depth"}},
      {P::Seed, {"seed"}},
      {P::Sampler, {"sampler"}},
      {P::Accelerator, {"accel"}},
      {P::Roulette, {"roulette"}},
      {P::Lookfrom, {"lookfrom"}},
      {P::Lookat, {"lookat"}},
      {P::Vup, {"vup"}},
      {P::Vfov, {"vfov"}},
      {P::Aperture, {"aperture"}},
      {P::FocusDistance, {"focus_distance"}},
      {P::Fresnel, {"fresnel"}},
      {P::StatsChannels, {"stats_channels"}},
      {P::Passes, {"passes"}},
      {P::Denoise, {"denoise"}},
      {P::Reproducible, {"reproducible"}},
  };
  return table;
}

}  // namespace

std::set<RequestPart> parts_given(const std::function<bool(std::string_view setting)>& given) {
  std::set<RequestPart> parts;
  for (const auto& [part, settings] : part_settings()) {
    for (const std::string_view setting : settings) {
      if (given(setting)) parts.insert(part);
    }
  }
  return parts;
}

}  // namespace rtiow
