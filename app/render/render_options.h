#pragma once
// `rtiow render`'s options: what the user typed (declared in app/command_line.cpp, in the
// order --help lists them), turned into the request the core gives meaning to
// (core/render/render_job.h).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/render/render_job.h"
#include "core/scene/builtin_scenes.h"

namespace rtiow {

struct RenderOptions {
  std::string scene_file;
  std::string like;  // an image whose recorded request this render repeats
  std::string scene = "cover";
  std::uint64_t scene_seed = kDefaultSceneSeed;
  bool list_scenes = false;
  std::string output;
  std::optional<int> width, height, spp, depth;
  std::vector<int> crop;  // X0,Y0,X1,Y1, or empty
  std::uint64_t seed = RenderRequest{}.seed;
  int threads = RenderRequest{}.threads;
  std::string accel = to_string(RenderRequest{}.accel);
  std::string fresnel;  // empty: as the scene says
  double time_limit = 0.0;
  std::string sampler = to_string(RenderRequest{}.sampler);
  std::string roulette = roulette_name(RenderRequest{}.russian_roulette);
  double target_error = 0.0;
  double image_error = 0.0;
  bool adaptive = false;
  std::optional<int> min_spp;
  bool stats_channels = false;
  bool denoise = false;
  std::string passes;  // "albedo,normal,depth" or a part of it; empty: none
  bool quiet = false;
  std::string summary_json;      // empty: none
  double preview_seconds = 0.0;  // > 0: replace the output with the samples so far this often
  std::string display;           // HOST:PORT of a tev viewer, or empty
  bool reproducible = false;
  double checkpoint_seconds = 60.0;  // 0: none
  bool resume = false;
  bool restart = false;
  bool keep_state = false;
  std::string sample_range;  // "A:B": render a share of the samples into a part file
  std::string part;          // "i/n": the i-th of n equal shares
  std::vector<double> lookfrom, lookat, vup;
  std::optional<double> vfov, aperture, focus_distance;
};

// The options as the core's request: `scene_named` and `output_given` say which were given;
// `rank` of `ranks` is this process's place under mpirun (0 of 1 otherwise). Throws
// InvalidInput for a --sampler or --accel the core does not know.
JobRequest job_request_of(const RenderOptions& o, bool scene_named, bool output_given, int rank,
                          int ranks);

}  // namespace rtiow
