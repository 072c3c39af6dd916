#include "core/measure/accuracy_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/limits/setting_name.h"
#include "core/measure/accuracy_fits.h"
#include "core/measure/accuracy_options.h"
#include "core/measure/accuracy_reference.h"
#include "core/measure/accuracy_report.h"
#include "core/measure/accuracy_runs.h"
#include "core/measure/figure_outputs.h"
#include "core/measure/figures.h"
#include "core/measure/measure_summary.h"
#include "core/parallel/thread_count.h"
#include "core/render/render.h"
#include "core/render/render_request.h"
#include "core/scene/builtin_scenes.h"

namespace rtiow {
namespace {

namespace fs = std::filesystem;
using json = Figures;

// The seed of the reference: far from the seeds users pick, so the measured renders are
// independent of it.
constexpr std::uint64_t kReferenceSeed = 0x5eed0000acc0ull;

std::string default_cache_dir() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    return (fs::path(xdg) / "rtiow").string();
  }
  if (const char* home = std::getenv("HOME"); home && *home) {
    return (fs::path(home) / ".cache" / "rtiow").string();
  }
  return ".rtiow-cache";
}

// The measured renders' request: the scene's depth and aspect ratio at the given width, the
// book's independent sampler (the reference's and the comparisons').
RenderRequest base_request(const AccuracyOptions& o) {
  RenderRequest r;
  r.width = o.width;
  r.threads = o.threads;
  r.seed = o.seed;
  r.sampler = SamplerKind::Independent;
  r.spp = o.reference_spp;
  return r;
}

}  // namespace

int run_accuracy(const AccuracyOptions& o) {
  const Scene scene = make_builtin_scene(o.scene, o.scene_seed);
  const RenderSettings base = resolve(scene, base_request(o)).settings;
  const std::unique_ptr<OutputClaim> summary = claim_summary(o.summary_json);
  const FigureOutputs outputs(o.out_dir, {"accuracy.json", "accuracy.csv", "accuracy.png"},
                              setting("out"));
  const std::string cache_dir = o.cache_dir.empty() ? default_cache_dir() : o.cache_dir;

  RenderSettings reference_settings = base;
  reference_settings.seed = kReferenceSeed;
  const Reference reference =
      load_or_render_reference(scene, reference_settings, cache_dir, o.quiet, !o.cache_dir.empty());
  if (!o.quiet && reference.reused) {
    std::fprintf(stderr, "accuracy: reusing the reference %s\n", reference.path.c_str());
  }

  json r = {{"scene", scene.name},
            {"width", base.width},
            {"height", base.height},
            {"depth", base.max_depth},
            {"seed", o.seed},
            {"reference_spp", o.reference_spp},
            {"reference_seed", kReferenceSeed},
            {"reference_path", reference.path},
            {"reference_reused", reference.reused},
            {"fixed_spp", o.fixed_spp},
            {"max_spp", o.max_spp},
            {"repeat", o.repeat},
            {"threads", thread_count(o.threads)}};
  run_sweeps(o, scene, base_request(o), reference.image, r);

  r["summary"] = summarise(r, o);
  print_table(r);
  const MeasureFiles files = write_figures(o, r);
  if (summary) write_text_atomically(o.summary_json, accuracy_summary_json(r, files));
  return 0;
}

}  // namespace rtiow
