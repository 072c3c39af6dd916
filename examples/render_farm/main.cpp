// What a render farm does with rtiow, through <rtiow/rtiow.h> alone, each checked against one
// uninterrupted render of the same request, bit for bit:
//  - a render stopped part way (as a machine is taken back) keeps its state in a checkpoint,
//    and a second render continues from it;
//  - a render split into two shares of the samples, each rendered and written as a part file
//    on its own, is merged into the image one render of all the samples gives.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <rtiow/rtiow.h>

namespace {

bool same_pixels(const rtiow::Film& a, const rtiow::Film& b) {
  return a.pixels().size() == b.pixels().size() &&
         std::memcmp(a.pixels().data(), b.pixels().data(),
                     a.pixels().size() * sizeof(rtiow::Color)) == 0;
}

// Stops the render at its first safe point (where its state is saved), then continues it.
bool stopped_and_resumed(const rtiow::Scene& scene, const rtiow::RenderSettings& job,
                         const std::string& checkpoint, const rtiow::Film& whole) {
  const rtiow::RenderIdentity identity = rtiow::render_identity(scene, job);
  rtiow::RenderProgress progress;
  rtiow::Checkpointing keep;
  keep.interval_seconds = 1e-9;  // save at every safe point
  keep.save = [&](const rtiow::RenderState& state, rtiow::SaveReason) {
    rtiow::write_checkpoint(checkpoint, identity, state);
    progress.stop_requested = true;  // the machine is taken back
  };
  const rtiow::RenderResult stopped = rtiow::render(scene, job, &progress, &keep);

  std::optional<rtiow::RenderState> state = rtiow::read_checkpoint(checkpoint, identity, job);
  if (!state) throw std::runtime_error("no checkpoint was written");
  rtiow::Checkpointing resume;
  resume.resume = &*state;
  const rtiow::RenderResult resumed = rtiow::render(scene, job, nullptr, &resume);
  std::printf("stopped at %d of %d spp, resumed to %d: %s one render\n", stopped.samples_completed,
              std::get<rtiow::FixedSamples>(job.samples).per_pixel, resumed.samples_completed,
              same_pixels(resumed.film, whole) ? "identical to" : "NOT the same as");
  return stopped.stopped && same_pixels(resumed.film, whole);
}

// Samples [0, 4) and [4, 8) of every pixel as two part files, merged.
bool parts_merged(const rtiow::Scene& scene, const rtiow::RenderSettings& job,
                  const std::filesystem::path& dir, const rtiow::Film& whole) {
  const auto job_samples = std::uint64_t(std::get<rtiow::FixedSamples>(job.samples).per_pixel);
  std::vector<std::string> parts;
  for (const std::uint64_t first : {std::uint64_t(0), job_samples / 2}) {
    rtiow::RenderSettings share = job;
    share.first_sample = first;
    share.samples = rtiow::FixedSamples{int(job_samples / 2)};
    const rtiow::RenderResult result = rtiow::render(scene, share);
    const std::string path = (dir / ("part" + std::to_string(parts.size()) + ".exr")).string();
    rtiow::write_part(path,
                      rtiow::make_part(scene, share, job_samples, result,
                                       rtiow::render_metadata(scene, share, result, true)),
                      result.sums);
    parts.push_back(path);
  }
  const rtiow::MergedImage merged = rtiow::merge_part_files(parts, {});
  const std::string output = (dir / "merged.exr").string();
  rtiow::write_image(output, merged.film, merged.metadata, merged.channels, merged.placement);
  std::printf("merged %zu parts: %dx%d, %llu spp -> %s: %s one render\n", merged.parts,
              merged.film.width(), merged.film.height(),
              static_cast<unsigned long long>(merged.samples), output.c_str(),
              same_pixels(merged.film, whole) ? "identical to" : "NOT the same as");
  return same_pixels(merged.film, whole);
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path dir = argc > 1 ? argv[1] : ".";
  try {
    const rtiow::Scene scene = rtiow::make_builtin_scene("cover", 1);
    rtiow::RenderSettings job;
    job.width = 160;
    job.samples = rtiow::FixedSamples{64};
    job = rtiow::with_scene_image(scene, job);  // the height the scene's aspect gives
    const rtiow::Film whole = rtiow::render(scene, job).film;
    const bool resumed = stopped_and_resumed(scene, job, (dir / "farm.checkpoint").string(), whole);
    const bool merged = parts_merged(scene, job, dir, whole);
    return resumed && merged ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_farm: error: %s\n", e.what());
    return 1;
  }
}
