#pragma once
// `rtiow accuracy`'s settings: the scene, the reference, the sweeps and where the figures go.

#include <cstdint>
#include <string>
#include <vector>

#include "core/render/render_request.h"
#include "core/render/render_settings.h"
#include "core/scene/builtin_scenes.h"

namespace rtiow {

struct AccuracyOptions {
  std::string scene = "cover";
  std::uint64_t scene_seed = kDefaultSceneSeed;
  int width = 160;
  int reference_spp = 8192;
  int max_spp = 1024;
  int fixed_spp = 64;
  std::uint64_t seed = RenderRequest{}.seed;
  int threads = 0;
  int repeat = 3;
  std::vector<int> depths{1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 50};
  std::vector<double> target_errors{0.2, 0.1, 0.07, 0.05, 0.035};
  std::vector<double> image_errors{0.1, 0.05, 0.03, 0.02};
  int book_spp = 500;  // the book's choice: its quality is the headline's goal
  std::string out_dir = "accuracy";
  std::string cache_dir;     // default: $XDG_CACHE_HOME/rtiow or ~/.cache/rtiow
  std::string summary_json;  // empty: none
  bool quiet = false;
  bool quick = false;
};

// The samplers every sweep compares, the book's first.
inline constexpr SamplerKind kAccuracySamplers[] = {SamplerKind::Independent, SamplerKind::Sobol,
                                                    SamplerKind::PaddedSobol};

}  // namespace rtiow
