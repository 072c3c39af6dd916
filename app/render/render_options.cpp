#include "app/render/render_options.h"

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/render/render_request.h"

namespace rtiow {
namespace {

Vec3d to_vec3(const std::vector<double>& v) {
  return {v[0], v[1], v[2]};
}

// The options as the core's request of a render.
RenderRequest request_of(const RenderOptions& o) {
  RenderRequest r;
  r.width = o.width, r.height = o.height;
  if (!o.crop.empty()) r.crop = PixelRegion{o.crop[0], o.crop[1], o.crop[2], o.crop[3]};
  r.spp = o.spp;
  r.max_depth = o.depth;
  CameraOverrides& cam = r.camera;
  if (!o.lookfrom.empty()) cam.lookfrom = to_vec3(o.lookfrom);
  if (!o.lookat.empty()) cam.lookat = to_vec3(o.lookat);
  if (!o.vup.empty()) cam.vup = to_vec3(o.vup);
  cam.vfov_degrees = o.vfov, cam.aperture = o.aperture, cam.focus_distance = o.focus_distance;
  if (!o.fresnel.empty()) r.fresnel = parse_fresnel(o.fresnel).value();  // CLI11 checked it
  r.sampler = parse_sampler(o.sampler);
  r.accel = parse_accel(o.accel);
  r.seed = o.seed;
  r.threads = o.threads;
  r.time_limit_seconds = o.time_limit;
  r.target_error = o.target_error;
  r.image_error = o.image_error;
  r.adaptive = o.adaptive;
  r.min_samples = o.min_spp;
  r.estimate_error = o.stats_channels;
  r.russian_roulette = o.roulette == roulette_name(true);  // CLI11 checked it is on or off
  if (!o.passes.empty()) {
    try {
      r.passes = parse_passes(o.passes);
    } catch (const InvalidInput& e) {
      throw InvalidInput(std::string("--passes: ") + e.what());
    }
  }
  return r;
}

}  // namespace

JobRequest job_request_of(const RenderOptions& o, bool scene_named, bool output_given, int rank,
                          int ranks) {
  JobRequest job;
  job.request = request_of(o);  // a bad --sampler or --accel before anything else
  job.scene_file = o.scene_file;
  job.scene = o.scene, job.scene_seed = o.scene_seed, job.scene_named = scene_named;
  job.output = o.output, job.output_given = output_given;
  job.sample_range = o.sample_range, job.part = o.part;
  job.rank = rank, job.ranks = ranks;
  job.stats_channels = o.stats_channels;
  job.denoise = o.denoise;
  if (!o.like.empty()) job.other_inputs.push_back(o.like);
  return job;
}

}  // namespace rtiow
