#include "app/render/image_request.h"

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "core/io/image_output.h"

namespace rtiow {
namespace {

// The options that give each part: any one of them makes the whole part the user's.
const std::vector<std::pair<RequestPart, std::vector<std::string>>>& part_options() {
  using P = RequestPart;
  static const std::vector<std::pair<P, std::vector<std::string>>> table = {
      {P::Scene, {"scene_file", "--scene"}},
      {P::SceneSeed, {"--scene-seed", "scene_file"}},  // a layout goes with a built-in scene
      {P::Size, {"--width", "--height"}},
      {P::Crop, {"--crop"}},
      {P::Samples,
       {"--spp", "--target-error", "--image-error", "--adaptive", "--min-spp", "--time-limit"}},
      {P::Depth, {"--depth"}},
      {P::Seed, {"--seed"}},
      {P::Sampler, {"--sampler"}},
      {P::Accelerator, {"--accel"}},
      {P::Roulette, {"--roulette"}},
      {P::Lookfrom, {"--lookfrom"}},
      {P::Lookat, {"--lookat"}},
      {P::Vup, {"--vup"}},
      {P::Vfov, {"--vfov"}},
      {P::Aperture, {"--aperture"}},
      {P::FocusDistance, {"--focus-dist"}},
      {P::Fresnel, {"--fresnel"}},
      {P::StatsChannels, {"--stats-channels"}},
      {P::Passes, {"--passes"}},
      {P::Reproducible, {"--reproducible"}},
  };
  return table;
}

}  // namespace

std::set<RequestPart> parts_given(const std::function<bool(const std::string& option)>& typed) {
  std::set<RequestPart> given;
  for (const auto& [part, options] : part_options()) {
    for (const std::string& name : options) {
      if (typed(name)) given.insert(part);
    }
  }
  return given;
}

}  // namespace rtiow
