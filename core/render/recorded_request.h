#pragma once
// The request an image's provenance records (its rtiow:* keys, core/render/render_metadata.h),
// so that the image can be rendered again, or rendered again with some of it changed: the
// library reads it and lays it under what a caller asks for, part by part. `rtiow render
// --like IMAGE` is this with the options the user typed on top.

#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>

#include "core/render/render_job.h"

namespace rtiow {

// What a caller's request replaces as a whole: a part it gives is its own, every other part
// is the image's.
enum class RequestPart {
  Scene,      // the scene file, or the built-in scene
  SceneSeed,  // the built-in scene's layout
  Size,       // the frame's width and height
  Crop,       // the region of the frame
  Samples,    // how many samples, and how they are spent (every adaptive mode, the time limit)
  Depth,
  Seed,
  Sampler,
  Accelerator,
  Roulette,
  Lookfrom,
  Lookat,
  Vup,
  Vfov,
  Aperture,
  FocusDistance,
  Fresnel,
  StatsChannels,  // the replicates an error estimate needs, and their channels
  Passes,
  Denoise,       // the image written denoised (and so the halves and first hits kept)
  Reproducible,  // no wall-clock time in the file, so it is byte for byte the same
};

struct RecordedRequest {
  std::string source;  // how messages name the image ("image 'a.png'")
  // The image's scene (a file, or a built-in scene and its layout) and request.
  JobRequest job;
  bool reproducible = false;
  // The parts a render cannot repeat (a time limit's budget, an adaptive render a signal
  // stopped), with why: refused unless the caller gives that part.
  std::map<RequestPart, std::string> unrepeatable;
  // What the recorded scene must digest to once the recorded camera and glass are applied:
  // a scene file edited since gives another digest.
  std::string scene_digest;
  std::string version;  // the rtiow that rendered it
};

// The parts of a request a caller gave a setting of, from whether each setting, by the
// library's name ("spp", "scene_file", "focus_distance"), was given: any one of a part's makes
// the whole part the caller's.
std::set<RequestPart> parts_given(const std::function<bool(std::string_view setting)>& given);

// Reads the request `path`'s header records; `source` names the image in messages. Throws
// InvalidInput naming the image and what is missing where it holds no request (a format
// without text, an older rtiow, a part file) or a value no render takes.
RecordedRequest read_recorded_request(const std::string& path, const std::string& source);

// `asked` with every part that is not in `given` taken from the image. `output_holds_channels`:
// whether the output keeps channels beyond R, G and B (the passes an image recorded are
// written again there, and left out elsewhere: they never change the image). Throws
// InvalidInput where a part left to the image is one no render repeats, where a new frame
// size would silently drop the image's region, or where the image's replicates need an
// output that can hold their channels. `reproducible` is the caller's, and the image's where
// the caller left it.
JobRequest overlay_recorded(const RecordedRequest& image, JobRequest asked,
                            const std::set<RequestPart>& given, bool output_holds_channels,
                            bool& reproducible);

// Throws InvalidInput where `scene`, with the image's camera and glass model, is not the scene
// the image was rendered from (a scene file edited since, or another rtiow's built-in scene).
void check_scene_of_image(const RecordedRequest& image, const Scene& scene);

}  // namespace rtiow
