#include "core/render/render.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>

#include "core/accel/embree_accel.h"
#include "core/accel/naive_accel.h"
#include "core/io/error.h"
#include "core/io/input_limits.h"
#include "core/render/render_loop.h"
#include "core/scene/camera.h"

namespace rtiow {
namespace {

// Beyond this many pixels indices overflow; a film costs this much per pixel (the float
// image and the exact fixed-point sums).
constexpr std::uint64_t kMaxPixels = 1ull << 31;
constexpr std::uint64_t kBytesPerPixel =
    sizeof(Color) + sizeof(PixelSum) + sizeof(PixelSquares) + sizeof(std::uint32_t);

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

// Every pixel gets the same samples, in passes of about a second.
template <typename Accel>
void render_uniform(const Scene& scene, const Camera& camera, const Accel& accel,
                    const RenderSettings& settings, RenderProgress* progress,
                    PixelAccumulators& pixels, RenderResult& result) {
  const auto render_start = Clock::now();
  const auto total = std::uint64_t(settings.samples_per_pixel);
  std::uint64_t done = 0, pass = 1;
  while (done < total) {
    if (done > 0 && progress->stop_requested.load()) {
      result.stopped = true;
      break;
    }
    const auto pass_start = Clock::now();
    result.rays_traced +=
        render_pass(scene, camera, accel, settings, std::uint32_t(done + pass), pixels, progress);
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
  result.samples_completed = int(done);
}

// The relative variance per sample a pixel is judged by: the mean of its neighbours' in
// the 3x3 window around it, itself left out. A rule that looked at the pixel's own samples
// would stop more often after lucky ones (a bright sample lowers the relative error, a
// missed rare path the variance) and bias the pixel; its neighbours' samples are
// independent of its own, so its mean stays unbiased. A 1x1 image has no neighbours and
// uses its own.
std::vector<double> neighbourhood_relative_variance(const RenderSettings& settings,
                                                    const PixelAccumulators& pixels) {
  const int w = settings.width, h = settings.height;
  std::vector<double> own(pixels.samples.size());
  for (std::size_t p = 0; p < own.size(); ++p) {
    own[p] = relative_sample_variance(pixels.sums[p], pixels.squares[p], pixels.samples[p]);
  }
  std::vector<double> judged(own.size());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double total = 0;
      int count = 0;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          total += own[std::size_t(ny) * std::size_t(w) + std::size_t(nx)];
          ++count;
        }
      }
      const std::size_t p = std::size_t(y) * std::size_t(w) + std::size_t(x);
      judged[p] = count > 0 ? total / count : own[p];
    }
  }
  return judged;
}

// Adaptive sampling: every pixel takes the minimum, then each round doubles the samples of
// the pixels whose estimated relative standard error is still above the target (up to the
// maximum). Decisions are made for all pixels before a round renders, from counts and sums
// that do not depend on timing, so the image is the same for any thread count. Few looks
// (one per doubling) and the neighbour-based estimate keep the stopping rule's bias small.
// A stop request or the time limit ends the render mid-round; untouched pixels keep their
// samples.
template <typename Accel>
void render_adaptive(const Scene& scene, const Camera& camera, const Accel& accel,
                     const RenderSettings& settings, RenderProgress* progress,
                     PixelAccumulators& pixels, RenderResult& result) {
  const auto render_start = Clock::now();
  const auto most = std::uint32_t(settings.samples_per_pixel);
  const auto least = std::min(most, std::uint32_t(settings.min_samples));
  const double target_variance = settings.target_error * settings.target_error;
  std::atomic<bool> stop_requested{false}, time_out{false};
  const std::function<bool()> may_skip = [&] {
    if (progress->stop_requested.load()) stop_requested = true;
    if (settings.time_limit_seconds > 0.0 &&
        seconds_since(render_start) >= settings.time_limit_seconds) {
      time_out = true;
    }
    return stop_requested.load() || time_out.load();
  };
  std::vector<std::uint32_t> targets(pixels.samples.size(), least);
  std::vector<std::size_t> list(pixels.samples.size());
  for (std::size_t p = 0; p < list.size(); ++p) list[p] = p;
  // The first round is never cut short: every pixel gets its minimum, so none is empty.
  const std::function<bool()> never = [] { return false; };
  for (bool first_round = true; !list.empty(); first_round = false) {
    result.rays_traced += render_pixel_list(scene, camera, accel, settings, list, targets, pixels,
                                            progress, first_round ? never : may_skip);
    if (stop_requested || time_out) break;
    const std::vector<double> judged = neighbourhood_relative_variance(settings, pixels);
    list.clear();
    for (std::size_t p = 0; p < targets.size(); ++p) {
      const std::uint32_t n = pixels.samples[p];
      if (n >= most || judged[p] / double(n) <= target_variance) continue;
      targets[p] = std::min(most, 2 * n);
      list.push_back(p);
    }
  }
  result.stopped = stop_requested.load();
  result.time_limited = time_out.load() && !result.stopped;
  result.samples_completed = int(*std::max_element(pixels.samples.begin(), pixels.samples.end()));
}

template <typename Accel>
RenderResult render_with(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         RenderProgress* progress) {
  RenderProgress unobserved;
  if (!progress) progress = &unobserved;
  RenderResult result;
  const auto build_start = Clock::now();
  const Accel accel(scene.spheres);
  result.build_seconds = seconds_since(build_start);

  PixelAccumulators pixels(std::size_t(settings.width) * std::size_t(settings.height));
  const auto render_start = Clock::now();
  if (settings.target_error > 0.0) {
    render_adaptive(scene, camera, accel, settings, progress, pixels, result);
  } else {
    render_uniform(scene, camera, accel, settings, progress, pixels, result);
  }
  result.render_seconds = seconds_since(render_start);
  result.film = Film(settings.width, settings.height);
  resolve(pixels.sums, pixels.samples, result.film);
  result.sums = std::move(pixels.sums);
  result.squares = std::move(pixels.squares);
  result.pixel_samples = std::move(pixels.samples);
  return result;
}

}  // namespace

std::string to_string(AccelKind kind) {
  return kind == AccelKind::Embree ? EmbreeAccel::name() : NaiveAccel::name();
}

std::string to_string(SamplerKind kind) {
  return kind == SamplerKind::Independent ? "independent" : "sobol";
}

SamplerKind parse_sampler(const std::string& name) {
  if (name == "independent") return SamplerKind::Independent;
  if (name == "sobol") return SamplerKind::Sobol;
  throw InvalidInput("unknown sampler '" + name + "' (known: independent, sobol)");
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
  if (s.width > limits::kMaxImageSide || s.height > limits::kMaxImageSide) {
    throw InvalidInput("image " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                       ": each side must be at most " + std::to_string(limits::kMaxImageSide));
  }
  if (s.max_depth < 0 || s.max_depth > limits::kMaxDepth) {
    throw InvalidInput("depth must be from 0 to " + std::to_string(limits::kMaxDepth) + ", got " +
                       std::to_string(s.max_depth));
  }
  if (s.threads < 0 || s.threads > limits::kMaxThreads) {
    throw InvalidInput("threads must be from 0 (all cores) to " +
                       std::to_string(limits::kMaxThreads) + ", got " + std::to_string(s.threads));
  }
  if (!(s.time_limit_seconds >= 0.0) || !std::isfinite(s.time_limit_seconds)) {
    throw InvalidInput("time limit must be a finite number of seconds >= 0");
  }
  if (s.first_sample > limits::kMaxSampleIndex ||
      s.first_sample + std::uint64_t(std::max(s.samples_per_pixel, 0)) > limits::kMaxSampleIndex) {
    throw InvalidInput("samples " + std::to_string(s.first_sample) + " to " +
                       std::to_string(s.first_sample + std::uint64_t(s.samples_per_pixel)) +
                       " go beyond sample index 2^32");
  }
  if (!(s.target_error >= 0.0) || !std::isfinite(s.target_error)) {
    throw InvalidInput("target error must be a finite number >= 0 (0: off)");
  }
  if (s.min_samples < 2) {
    throw InvalidInput("minimum samples must be >= 2 (a variance needs two), got " +
                       std::to_string(s.min_samples));
  }
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

void validate(const Scene& scene, const RenderSettings& settings) {
  validate(settings);
  validate(scene);
  validate(scene.camera, settings.width, settings.height);
}

RenderResult render(const Scene& scene, const RenderSettings& settings, RenderProgress* progress) {
  validate(scene, settings);
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
