#include "app/render/image_request.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "core/io/image_backend.h"
#include "core/io/image_file.h"
#include "core/io/image_output.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/render/render_metadata.h"
#include "core/scene_file/scene_digest.h"

namespace rtiow {
namespace {

using Recorded = std::map<std::string, std::string>;  // key (without "rtiow:") -> text

// A float attribute (EXR stores doubles as floats) as the shortest text that reads back as
// that float: 0.05f is "0.05", the value the user typed, not 0.0500000007.
std::string float_text(float v) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, v).ptr);
}

void add_json_keys(const std::string& description, Recorded& recorded) {
  const auto all = nlohmann::json::parse(description, nullptr, /*allow_exceptions=*/false);
  if (!all.is_object()) return;
  const std::string prefix = kMetadataPrefix;
  for (const auto& [name, value] : all.items()) {
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string key = name.substr(prefix.size());
    if (value.is_string()) {
      recorded[key] = value.get<std::string>();
    } else if (value.is_number_integer()) {
      recorded[key] = value.dump();
    } else if (value.is_number_float()) {
      char text[32];
      recorded[key] =
          std::string(text, std::to_chars(text, text + sizeof text, value.get<double>()).ptr);
    }
  }
}

// Every rtiow:* key of the header: its own attributes (PNG, EXR), or the JSON object in the
// image description (JPEG, TIFF).
Recorded recorded_keys(const ImageHeader& header) {
  Recorded recorded;
  const std::string prefix = kMetadataPrefix;
  for (const ImageAttribute& a : header.attributes) {
    if (a.name == "ImageDescription") {
      if (const auto* text = std::get_if<std::string>(&a.value)) add_json_keys(*text, recorded);
      continue;
    }
    if (a.name.rfind(prefix, 0) != 0) continue;
    const std::string key = a.name.substr(prefix.size());
    if (const auto* i = std::get_if<int>(&a.value)) recorded[key] = std::to_string(*i);
    if (const auto* f = std::get_if<float>(&a.value)) recorded[key] = float_text(*f);
    if (const auto* s = std::get_if<std::string>(&a.value)) recorded[key] = *s;
  }
  return recorded;
}

// The shortest text that reads back as the same double.
std::string exact(double v) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, v).ptr);
}

class RequestBuilder {
 public:
  RequestBuilder(std::string image, Recorded recorded)
      : image_(std::move(image)), recorded_(std::move(recorded)) {}

  const std::string* find(const char* key) const {
    const auto it = recorded_.find(key);
    return it == recorded_.end() ? nullptr : &it->second;
  }
  const std::string& need(const char* key) const {
    if (const std::string* value = find(key)) return *value;
    throw InvalidInput(image_ + " has no rtiow:" + key +
                       ": it was written before rtiow recorded the whole request, or its "
                       "metadata was edited since");
  }
  [[noreturn]] void refuse(const std::string& why) const {
    throw InvalidInput(image_ + ": " + why);
  }

  void add(const std::string& group, const std::string& name, std::vector<std::string> values) {
    request_.options.push_back({group, name, std::move(values), {}});
  }
  // A part of the request no render repeats: refused unless the user gives that part.
  void unrepeatable(const std::string& group, const std::string& why) {
    request_.options.push_back({group, "", {}, image_ + ": " + why});
  }
  void add_copy(const char* key, const std::string& option) {
    if (const std::string* value = find(key)) add(option, option, {*value});
  }

  // The camera the image records (core/render/render_metadata.h), one option per setting.
  void add_camera() {
    const CameraOverrides c = read_camera_record(need(metadata_key::kCamera), image_);
    request_.camera = c;
    const auto vector = [&](const char* option, const std::optional<Vec3d>& v) {
      if (v) add(option, option, {exact(v->x) + "," + exact(v->y) + "," + exact(v->z)});
    };
    const auto scalar = [&](const char* option, const std::optional<double>& x) {
      if (x) add(option, option, {exact(*x)});
    };
    vector("--lookfrom", c.lookfrom), vector("--lookat", c.lookat), vector("--vup", c.vup);
    scalar("--vfov", c.vfov_degrees), scalar("--aperture", c.aperture);
    scalar("--focus-dist", c.focus_distance);
  }

  // How many samples, and how they were spent: one group, replaced whole by any sampling
  // option the user gives.
  void add_samples() {
    namespace key = metadata_key;
    const char* group = "samples";
    if (const std::string* spp = find(key::kSpp)) {
      // Uniform: the count completed, also where a signal or a time limit stopped it early.
      add(group, "--spp", {*spp});
      return;
    }
    if (const std::string* stopped = find(key::kStopped)) {
      unrepeatable(group, "its adaptive render was stopped early (" + quote_value(*stopped) +
                              "): where each pixel stopped depends on when; give the sampling "
                              "(--spp, --target-error, ...)");
      return;
    }
    if (const std::string* target = find(key::kTargetError)) {
      add(group, "--target-error", {*target});
      add(group, "--spp", {need(key::kSppLimit)});
    } else if (const std::string* image_error = find(key::kImageError)) {
      add(group, "--image-error", {*image_error});
      add(group, "--spp", {need(key::kSppLimit)});
    } else if (find(key::kAdaptive)) {
      const std::string* budget = find(key::kSppBudget);
      if (!budget) {
        unrepeatable(group,
                     "its adaptive budget was a time limit, which gives another image on "
                     "another machine; give the sampling (--spp, --time-limit, ...)");
        return;
      }
      add(group, "--adaptive", {});
      add(group, "--spp", {*budget});
    } else {
      need(key::kSpp);
    }
    if (const std::string* least = find(key::kMinSpp)) add(group, "--min-spp", {*least});
  }

  // The image's size, or for a crop the frame's size and the region (replaced by --crop, and
  // by --width or --height, which make another frame).
  void add_size(const ImageHeader& header) {
    namespace key = metadata_key;
    const std::string* crop = find(key::kCrop);
    const std::string* frame = find(key::kFrame);
    if (!crop && !frame) {
      add("size", "--width", {std::to_string(header.width)});
      add("size", "--height", {std::to_string(header.height)});
      return;
    }
    const Metadata recorded{{key::kCrop, crop ? *crop : std::string()},
                            {key::kFrame, frame ? *frame : std::string()}};
    const FramePlacement place = recorded_placement(recorded, image_, header.width, header.height);
    add("size", "--width", {std::to_string(place.frame_width)});
    add("size", "--height", {std::to_string(place.frame_height)});
    add("crop", "--crop",
        {std::to_string(place.x), std::to_string(place.y), std::to_string(place.x + header.width),
         std::to_string(place.y + header.height)});
  }

  ImageRequest build(const ImageHeader& header) {
    namespace key = metadata_key;
    if (recorded_.empty()) {
      refuse(
          "holds no rtiow provenance (HDR, PPM, BMP and TGA keep none; PNG, EXR, JPEG and "
          "TIFF do)");
    }
    if (find("part_samples")) {
      refuse(
          "is a part of a shared render: merge the parts (rtiow merge) and use the merged "
          "image");
    }
    request_.scene_digest = need(key::kSceneDigest);
    request_.version = need(key::kVersion);
    if (const std::string* file = find(key::kSceneFile)) {
      add("scene", "scene_file", {*file});
      request_.scene_file = *file;
    } else {
      add("scene", "--scene", {need(key::kScene)});
      if (const std::string* seed = find(key::kSceneSeed)) {
        add("--scene-seed", "--scene-seed", {*seed});
      }
    }
    add_size(header);
    add_samples();
    add("--depth", "--depth", {need(key::kDepth)});
    add("--seed", "--seed", {need(key::kSeed)});
    add("--sampler", "--sampler", {need(key::kSampler)});
    add_copy(key::kAccelerator, "--accel");
    add_copy(key::kRussianRoulette, "--roulette");  // absent in older files: on
    add_camera();
    if (const std::string* fresnel = find(key::kFresnel)) {
      // One model for all the glass: as --fresnel gave it, or as the scene said (the same).
      if (const auto model = parse_fresnel(*fresnel)) {
        request_.fresnel = model;
        add("--fresnel", "--fresnel", {*fresnel});
      }
    }
    // The statistics channels, or two replicates in a uniform render or on an adaptive budget
    // (the error targets keep two whatever was asked): --stats-channels was given.
    const std::string* replicates = find(key::kReplicates);
    const auto& channels = header.channel_names;
    if (std::find(channels.begin(), channels.end(), "variance.R") != channels.end() ||
        (replicates && *replicates == "2" && (find(key::kSpp) || find(key::kAdaptive)))) {
      add("--stats-channels", "--stats-channels", {});
    }
    if (const std::string* passes = find(key::kPasses)) {
      try {
        parse_passes(*passes);
      } catch (const InvalidInput&) {
        refuse(std::string(kMetadataPrefix) + key::kPasses + " " + quote_value(*passes) +
               " is not a list of passes (" + pass_names() + ")");
      }
      add("--passes", "--passes", {*passes});
    }
    if (!find(key::kRenderSeconds)) add("--reproducible", "--reproducible", {});
    return std::move(request_);
  }

 private:
  std::string image_;
  Recorded recorded_;
  ImageRequest request_;
};

}  // namespace

ImageRequest read_image_request(const std::string& path) {
  const std::string name = "--like image " + quote_value(path);
  const auto in = open_input_image(path, name, limits::kMaxPartFileBytes, "image");
  RequestBuilder builder(name, recorded_keys(in->header()));
  return builder.build(in->header());
}

namespace {

// The options that replace a group: any of its members given by the user.
std::vector<std::string> members(const std::string& group) {
  // A seed of the layout goes with a built-in scene, not a file.
  if (group == "scene") return {"scene_file", "--scene"};
  if (group == "--scene-seed") return {"--scene-seed", "scene_file"};
  if (group == "size") return {"--width", "--height"};
  if (group == "crop") return {"--crop", "--width", "--height"};
  if (group == "samples") {
    return {"--spp", "--target-error", "--image-error", "--adaptive", "--min-spp", "--time-limit"};
  }
  return {group};
}

bool given(CLI::App& render, const std::string& group) {
  for (const std::string& name : members(group)) {
    if (render.get_option(name)->count() > 0) return true;
  }
  return false;
}

// Whether the output holds channels beyond R, G, B: the passes an image recorded are written
// again there, and left out of a format that cannot hold them (they never change the image).
bool output_holds_channels(CLI::App& render) {
  CLI::Option* output = render.get_option("--output");
  const ImageFormat* format =
      output->count() > 0 ? image_format(output->as<std::string>()) : nullptr;
  return format && format->extra_channels;
}

// Two replicates give other pixels than one sequence, and only .exr holds the channels that
// --stats-channels adds: the image's pixels are rendered again only into an .exr.
void check_room_for_replicates(CLI::App& render) {
  if (output_holds_channels(render)) return;
  const std::string image = render.get_option("--like")->as<std::string>();
  throw InvalidInput("--like image " + quote_value(image) +
                     " was rendered with --stats-channels, whose two replicates give other "
                     "pixels than one sequence: render it again into an .exr (-o NAME.exr)");
}

// The image records its scene file as it was given, relative to where that render ran: from
// elsewhere it names no file, and the user is told where the name came from.
void check_recorded_scene_file(const std::string& scene_file, CLI::App& render) {
  std::error_code error;
  if (std::filesystem::exists(scene_file, error)) return;
  const std::string image = render.get_option("--like")->as<std::string>();
  const bool relative = std::filesystem::path(scene_file).is_relative();
  throw InvalidInput("--like image " + quote_value(image) + " was rendered from scene file " +
                     quote_value(scene_file) +
                     (relative ? ", a name relative to the directory that render ran in; " : ", ") +
                     "there is no such file from here: give the scene file (rtiow render FILE "
                     "--like " +
                     quote_value(image) + ")");
}

}  // namespace

bool apply_image_request(const ImageRequest& request, CLI::App& render) {
  std::vector<const ImageRequest::Option*> taken;
  for (const ImageRequest::Option& o : request.options) {
    if (!given(render, o.group)) taken.push_back(&o);
    // A new frame size would drop the image's region without a word (issue 70).
    if (o.name == "--crop" && given(render, "size") && !given(render, "--crop")) {
      std::string region;
      for (const std::string& value : o.values) region += (region.empty() ? "" : ",") + value;
      throw InvalidInput("--like image " +
                         quote_value(render.get_option("--like")->as<std::string>()) +
                         " is the region " + region +
                         " of its frame; --width or --height makes another frame, whose region "
                         "it cannot know: give --crop too (--crop 0,0,W,H for the whole frame)");
    }
  }
  const bool scene_chosen = given(render, "scene") || given(render, "--scene-seed");
  if (!scene_chosen && !request.scene_file.empty()) {
    check_recorded_scene_file(request.scene_file, render);
  }
  for (const ImageRequest::Option* o : taken) {
    if (!o->unrepeatable.empty()) throw InvalidInput(o->unrepeatable);
    CLI::Option* option = render.get_option(o->name);
    if (o->name == "--stats-channels") check_room_for_replicates(render);
    if (o->name == "--passes" && !output_holds_channels(render)) continue;
    try {
      if (o->values.empty()) {
        option->add_result(std::string("true"));  // a flag
      } else {
        for (const std::string& value : o->values) option->add_result(value);
      }
      option->run_callback();  // checks the value and sets the option's variable
    } catch (const CLI::Error& e) {
      throw InvalidInput("--like image " +
                         quote_value(render.get_option("--like")->as<std::string>()) +
                         " records a value rtiow cannot use: " + e.what());
    }
  }
  return scene_chosen;
}

void check_scene_of_image(const ImageRequest& request, const Scene& scene,
                          const std::string& image) {
  RenderRequest as_recorded;
  as_recorded.camera = request.camera;
  as_recorded.fresnel = request.fresnel;
  const std::string digest = scene_digest(resolve(scene, as_recorded).scene);
  if (digest == request.scene_digest) return;
  const std::string which =
      request.scene_file.empty()
          ? "built-in scene " + quote_value(scene.name) + " is not the one rtiow " +
                quote_value(request.version) + " rendered it from"
          : "scene file " + quote_value(request.scene_file) +
                " is not the scene it was rendered from; the file changed since";
  throw InvalidInput("--like image " + quote_value(image) + ": " + which + " (digest " +
                     request.scene_digest + " then, " + digest +
                     " now); give the scene (a file or --scene) to render it anyway");
}

}  // namespace rtiow
