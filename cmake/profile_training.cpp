// The renders whose profile guides the optimised build (cmake/ProfileGuided.cmake), run through
// the library by an instrumented core, so that only the core is compiled twice: the book's cover
// with each sampler (the independent one as benchmarks time it), a glass-and-metal scene, an
// adaptive render, and a big scene written as a file and loaded from it (without it the load
// of a big scene, code the training barely ran, was compiled with less inlining than a build
// without a profile). Small, so the training takes seconds.
//   rtiow_profile_training WORK_DIR
// A failed render is reported and the others still run, and the exit status is 0: the paths it
// would have reached are compiled without a profile (as with -DRTIOW_PGO=OFF) rather than
// failing the build.
#include <cstdio>
#include <exception>
#include <fstream>
#include <functional>
#include <string>
#include <utility>

#include "core/rtiow.h"

namespace {

using rtiow::RenderRequest;

int failures = 0;

void train(const char* what, const std::function<void()>& job) {
  try {
    job();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "profile training: %s failed: %s\n", what, e.what());
    ++failures;
  }
}

RenderRequest small(int spp) {
  RenderRequest request;
  request.width = 160;
  request.height = 90;
  request.spp = spp;
  return request;
}

void render_scene(rtiow::Scene scene, const RenderRequest& request, const std::string& output) {
  const auto job = rtiow::resolve(std::move(scene), request);
  const rtiow::RenderResult result = rtiow::render(job.scene, job.settings);
  if (!output.empty()) rtiow::write_image(output, result.film);
}

void render_builtin(const std::string& name, const RenderRequest& request,
                    const std::string& output) {
  render_scene(rtiow::make_builtin_scene(name, rtiow::kDefaultSceneSeed), request, output);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: rtiow_profile_training WORK_DIR\n");
    return 2;
  }
  const std::string dir = argv[1];

  train("the cover, independent sampler (as bench-point)", [] {
    RenderRequest request = small(64);
    request.sampler = rtiow::SamplerKind::Independent;
    request.max_depth = 50;
    request.threads = 2;
    render_builtin("cover", request, "");
  });
  train("the cover, sobol", [&] { render_builtin("cover", small(64), dir + "/train-sobol.png"); });
  train("the cover, padded sobol", [&] {
    RenderRequest request = small(32);
    request.sampler = rtiow::SamplerKind::PaddedSobol;
    render_builtin("cover", request, dir + "/train-padded.png");
  });
  train("the materials scene",
        [&] { render_builtin("materials", small(64), dir + "/train-materials.png"); });
  train("an adaptive cover", [&] {
    RenderRequest request;
    request.width = 80;
    request.height = 45;
    request.image_error = 0.05;
    render_builtin("cover", request, dir + "/train-adaptive.png");
  });
  train("a big scene through a file", [&] {
    const std::string path = dir + "/train-spheres.json";
    std::ofstream(path) << rtiow::scene_to_json(
        rtiow::make_builtin_scene("spheres:100000", rtiow::kDefaultSceneSeed));
    RenderRequest request;
    request.width = 8;
    request.height = 8;
    request.spp = 1;
    render_scene(rtiow::load_scene_file(path), request, dir + "/train-spheres.png");
  });
  if (failures > 0)
    std::fprintf(stderr,
                 "profile training: %d render(s) failed; what they run is compiled "
                 "without a profile\n",
                 failures);
  return 0;
}
