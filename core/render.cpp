#include "core/render.h"

#include <chrono>
#include <cstdint>

#include "core/camera.h"
#include "core/embree_accel.h"
#include "core/error.h"
#include "core/naive_accel.h"
#include "core/render_loop.h"

namespace rtiow {
namespace {

// Beyond this many pixels the film alone would not fit in a machine's memory.
constexpr std::uint64_t kMaxPixels = 1ull << 31;

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

template <typename Accel>
RenderResult render_with(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         RenderProgress* progress) {
  RenderResult result;
  const auto build_start = Clock::now();
  const Accel accel(scene.spheres);
  result.build_seconds = seconds_since(build_start);

  result.film = Film(settings.width, settings.height);
  const auto render_start = Clock::now();
  result.rays_traced = render_tiles(scene, camera, accel, settings, result.film, progress);
  result.render_seconds = seconds_since(render_start);
  return result;
}

}  // namespace

std::string to_string(AccelKind kind) {
  return kind == AccelKind::Embree ? EmbreeAccel::name() : NaiveAccel::name();
}

AccelKind parse_accel(const std::string& name) {
  if (name == EmbreeAccel::name()) return AccelKind::Embree;
  if (name == NaiveAccel::name()) return AccelKind::Naive;
  throw InvalidInput("unknown accelerator '" + name + "' (known: embree, naive)");
}

void validate(const RenderSettings& s) {
  if (s.width <= 0) throw InvalidInput("width must be > 0, got " + std::to_string(s.width));
  if (s.height <= 0) throw InvalidInput("height must be > 0, got " + std::to_string(s.height));
  if (s.samples_per_pixel <= 0) {
    throw InvalidInput("spp must be > 0, got " + std::to_string(s.samples_per_pixel));
  }
  if (s.max_depth < 0) throw InvalidInput("depth must be >= 0, got " + std::to_string(s.max_depth));
  if (s.threads < 0) throw InvalidInput("threads must be >= 0, got " + std::to_string(s.threads));
  if (std::uint64_t(s.width) * std::uint64_t(s.height) > kMaxPixels) {
    throw InvalidInput("image " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                       " has more than 2^31 pixels");
  }
}

RenderResult render(const Scene& scene, const RenderSettings& settings, RenderProgress* progress) {
  validate(settings);
  const Camera camera(scene.camera, settings.width, settings.height);
  switch (settings.accel) {
    case AccelKind::Embree:
      return render_with<EmbreeAccel>(scene, camera, settings, progress);
    case AccelKind::Naive:
      return render_with<NaiveAccel>(scene, camera, settings, progress);
  }
  throw InvalidInput("unknown accelerator");
}

}  // namespace rtiow
