#pragma once
// A render as a command asks for it: which scene (a file or a built-in one), what to change
// about it (a RenderRequest), where the image goes, and which share of the samples this
// process renders. prepare_job() checks all of it before any work; write_job_result() writes
// the image, or the part file of a share.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/io/image_output.h"
#include "core/render/denoised_output.h"
#include "core/render/render_request.h"
#include "core/render/render_settings.h"
#include "core/scene/builtin_scenes.h"
#include "core/scene/scene.h"

namespace rtiow {

struct JobRequest {
  std::string scene_file;  // a path, or "-" for standard input; empty: the built-in `scene`
  std::string scene = "cover";
  std::uint64_t scene_seed = kDefaultSceneSeed;
  bool scene_named = false;  // `scene` was given (then a scene file is refused with it)
  std::string output;        // used when `output_given`; else <scene>.png
  bool output_given = false;
  RenderRequest request;
  // A share of the samples, at most one: "A:B" (--sample-range) or "i/n" (--part).
  std::string sample_range, part;
  int rank = 0, ranks = 1;  // under mpirun, this rank's equal share
  bool stats_channels = false;
  // --denoise: keep the halves and the first hits, and write the denoised image (a share keeps
  // them for the merge that denoises: core/render/part_merge.h).
  bool denoise = false;
  std::vector<std::string> other_inputs;  // files read besides the scene, never overwritten
  // Called with the scene once it is loaded, before anything is changed about it.
  std::function<void(const Scene&)> check_loaded_scene;
};

// A render as the request asks for it, checked: the scene, the settings of this process's
// share, and where it goes.
struct RenderJob {
  Scene scene;
  RenderSettings settings;
  std::string output;
  std::uint64_t samples_asked = 0;  // a shared job's whole count, before it is cut
  bool share = false;               // written as a part file
};

// The request the job renders: with --denoise, checked against what the denoiser cannot
// combine with, and keeping what it needs (the two independent halves, the first hits).
// Throws InvalidInput naming the conflict.
RenderRequest job_render_request(const JobRequest& request);

// Throws InvalidInput naming what is wrong, before any work (a bad -o before a large scene
// loads).
RenderJob prepare_job(const JobRequest& request);

// The same for a scene already built (a program's own, or the Python module's): the request's
// scene_file, scene and scene_seed are not read.
RenderJob prepare_job(const JobRequest& request, Scene scene);

// The scene the request names: its scene file (checked as any input), or the built-in scene
// and its layout. prepare_job() loads it so; a caller that sets the scene up first uses this.
Scene load_job_scene(const JobRequest& request);

// The image --denoise writes, made before the metadata that reports its figures: none where the
// request does not denoise, for a share (its part keeps the sums), where a render stopped before
// each half of every pixel had a sample, or where an end was asked for while it denoised (the
// image is then written as rendered). The denoiser's progress goes to `progress`, where given.
std::optional<DenoisedImage> denoise_for_output(const JobRequest& request, const RenderJob& job,
                                                const RenderResult& result,
                                                WorkProgress* progress = nullptr);

// The image (with the statistics channels where asked; `denoised`, from denoise_for_output(),
// where it made one) or, for a share, the part file.
void write_job_result(const JobRequest& request, const RenderJob& job, const RenderResult& result,
                      const Metadata& metadata, const DenoisedImage* denoised);

// The files the request reads: the scene file and the others.
std::vector<std::string> input_files(const JobRequest& request);

}  // namespace rtiow
