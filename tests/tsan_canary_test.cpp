// A deliberate data race inside the real sample loop. Built only under ThreadSanitizer and
// expected to FAIL: it proves that the suppressions in tests/tsan.supp and the annotations
// around tbb::parallel_for leave races in our loop body visible.

#include <gtest/gtest.h>

#include <chrono>
#include <optional>

#include "core/render/render_loop.h"
#include "core/scene/builtin_scenes.h"

namespace rtiow {
namespace {

// Counts queries in a plain int shared by all threads: a race. Each query also takes a few
// microseconds, so that both threads get tiles even on a loaded machine.
struct RacyAccel {
  mutable int queries = 0;
  std::optional<Hit> intersect(const Ray&, float, std::uint32_t) const {
    queries = queries + 1;
    const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(5);
    while (std::chrono::steady_clock::now() < until) {
    }
    return std::nullopt;
  }
};

TEST(TsanCanary, RaceInTheLoopBodyIsReported) {
  const Scene scene = make_builtin_scene("materials", 1);
  RenderSettings s;
  s.width = 128;
  s.height = 128;
  s.samples = FixedSamples{1};
  s.max_depth = 1;
  s.threads = 2;
  s.seed = 0, s.sampler = SamplerKind::Independent;
  const Camera camera(scene.camera, s.width, s.height);
  PixelAccumulators pixels(std::size_t(s.width * s.height));
  const RacyAccel accel;
  render_pass(RenderContext<RacyAccel>{scene, camera, accel, s}, 1, pixels, nullptr);
  EXPECT_GT(accel.queries, 0);
}

}  // namespace
}  // namespace rtiow
