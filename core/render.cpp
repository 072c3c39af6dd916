#include "core/render.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>

#include "core/camera.h"
#include "core/embree_accel.h"
#include "core/error.h"
#include "core/naive_accel.h"
#include "core/render_loop.h"

namespace rtiow {
namespace {

// Beyond this many pixels indices overflow; a film costs this much per pixel (the float
// image and the exact fixed-point sums).
constexpr std::uint64_t kMaxPixels = 1ull << 31;
constexpr std::uint64_t kBytesPerPixel = sizeof(Color) + sizeof(PixelSum);

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// How many samples the next pass takes: about a second's worth, judged from the last pass,
// so a stop request is honoured soon. (Grouping never changes the image.)
std::uint64_t next_pass_samples(std::uint64_t last_pass, double last_seconds,
                                std::uint64_t remaining) {
  constexpr double kTargetSeconds = 1.0;
  double n = double(last_pass) * (last_seconds > 0 ? kTargetSeconds / last_seconds : 4.0);
  n = std::clamp(n, 1.0, 4.0 * double(last_pass));
  return std::min(remaining, std::uint64_t(n));
}

template <typename Accel>
RenderResult render_with(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         RenderProgress* progress) {
  RenderResult result;
  const auto build_start = Clock::now();
  const Accel accel(scene.spheres);
  result.build_seconds = seconds_since(build_start);

  result.sums.resize(std::size_t(settings.width) * std::size_t(settings.height));
  const auto render_start = Clock::now();
  const std::uint64_t first = settings.first_sample;
  const auto total = std::uint64_t(settings.samples_per_pixel);
  std::uint64_t done = 0, pass = 1;
  while (done < total) {
    if (done > 0 && progress && progress->stop_requested.load()) {
      result.stopped = true;
      break;
    }
    const auto pass_start = Clock::now();
    result.rays_traced += render_pass(scene, camera, accel, settings, first + done,
                                      first + done + pass, result.sums, progress);
    done += pass;
    const double pass_seconds = seconds_since(pass_start);
    const double seconds_per_sample = pass_seconds / double(pass);
    pass = next_pass_samples(pass, pass_seconds, total - done);
    if (settings.time_limit_seconds > 0.0 && done < total) {
      // End within one pass of the limit: stop once it is reached, and size the next pass to
      // what the remaining time holds at the rate just measured.
      const double left = settings.time_limit_seconds - seconds_since(render_start);
      if (left <= 0.0) {
        result.time_limited = true;
        break;
      }
      const double fits = left / std::max(seconds_per_sample, 1e-9);
      pass = std::clamp<std::uint64_t>(std::uint64_t(fits), 1, pass);
    }
  }
  result.render_seconds = seconds_since(render_start);
  result.samples_completed = int(done);
  result.film = Film(settings.width, settings.height);
  resolve(result.sums, done, result.film);
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
  if (!(s.time_limit_seconds >= 0.0) || !std::isfinite(s.time_limit_seconds)) {
    throw InvalidInput("time limit must be a finite number of seconds >= 0");
  }
  if (s.first_sample > (1ull << 62)) throw InvalidInput("first sample index is out of range");
  const std::uint64_t pixels = std::uint64_t(s.width) * std::uint64_t(s.height);
  if (pixels > kMaxPixels) {
    throw InvalidInput("image " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                       " has more than 2^31 pixels");
  }
  // Refuse before allocating what the machine cannot hold: the film and its accumulator.
  const std::uint64_t needed = pixels * kBytesPerPixel;
  const std::uint64_t available =
      std::uint64_t(sysconf(_SC_PHYS_PAGES)) * std::uint64_t(sysconf(_SC_PAGESIZE));
  if (needed > available / 2) {
    throw InvalidInput("image " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                       " needs " + std::to_string(needed >> 20) +
                       " MiB, more than half of this machine's " + std::to_string(available >> 20) +
                       " MiB");
  }
}

RenderResult render(const Scene& scene, const RenderSettings& settings, RenderProgress* progress) {
  validate(settings);
  validate(scene);
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
