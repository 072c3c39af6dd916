#pragma once
// The high-sample reference `rtiow accuracy` measures against, cached on disk: an EXR with
// the image, each pixel's variance and, in its metadata, the digest of the scene and
// settings, the spp and the seed. It is reused only when all of them match.

#include <string>

#include "core/film/image_error.h"
#include "core/render/render.h"
#include "core/scene/scene.h"

namespace rtiow {

struct Reference {
  ImageEstimate image;
  std::string path;
  bool reused = false;        // read from the cache rather than rendered
  double render_seconds = 0;  // when rendered now
};

// Reads `<cache_dir>/reference-<digest>-<spp>spp.exr` if it matches (scene, settings),
// otherwise renders it (with a progress line unless `quiet`) and writes it there.
// `cache_dir_given`: the user named it (--cache-dir), rather than taking the default; a
// directory that cannot be made is said in their words.
Reference load_or_render_reference(const Scene& scene, const RenderSettings& settings,
                                   const std::string& cache_dir, bool quiet, bool cache_dir_given);

}  // namespace rtiow
