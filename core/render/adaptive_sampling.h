#pragma once
// Adaptive sampling: pixels take different numbers of samples, decided in rounds. Decisions
// are made for all pixels between rounds, from counts, sums and ray counts that do not
// depend on timing, so the image is the same for any thread count (a time limit decides only
// when the rounds end). Every pixel first takes the minimum; estimates are pooled from
// neighbours (core/render/sample_allocation.h), which keeps each pixel's mean unbiased.
// A stop request or the time limit ends the render mid-round; untouched pixels keep their
// samples.
//
// - render_adaptive (--target-error): each pixel takes more samples until its own relative
//   standard error is below the target.
// - render_by_image_error (--image-error, --adaptive): samples go where they lower the
//   image's mean relMSE most per ray, in proportion to sqrt(variance / cost).

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numeric>
#include <variant>
#include <vector>

#include "core/limits/input_limits.h"
#include "core/parallel/thread_count.h"
#include "core/render/render_loop.h"
#include "core/render/render_state.h"
#include "core/render/sample_allocation.h"
#include "core/render/stopwatch.h"

namespace rtiow {

// Asked before each group of pixels of a round: true once a stop is requested or the time
// limit has passed (counting the time spent before a resume), remembering which.
class RoundDeadline {
 public:
  RoundDeadline(const RenderSettings& settings, RenderProgress* progress,
                const RenderJournal& journal)
      : settings_(settings), progress_(progress), journal_(journal) {}

  bool operator()() {
    if (progress_->stop_requested.load()) stop_requested_ = true;
    if (settings_.time_limit_seconds > 0.0 && elapsed() >= settings_.time_limit_seconds) {
      time_out_ = true;
    }
    return stop_requested_.load() || time_out_.load();
  }

  double elapsed() const { return journal_.elapsed(); }
  bool ended() const { return stop_requested_.load() || time_out_.load(); }

  void report(RenderResult& result, const PixelAccumulators& pixels) const {
    result.stopped = stop_requested_.load();
    if (result.stopped) result.stop_cause = progress_->stop_cause;
    result.time_limited = time_out_.load() && !result.stopped;
    result.samples_completed = int(*std::max_element(pixels.samples.begin(), pixels.samples.end()));
  }

 private:
  const RenderSettings& settings_;
  RenderProgress* progress_;
  const RenderJournal& journal_;
  std::atomic<bool> stop_requested_{false}, time_out_{false};
};

// Renders the pixels whose target (the state's) is above their count. The first round is
// never cut short by the deadline: every pixel gets its minimum, so none is empty. A save
// that falls due pauses the round, saves it with its targets and goes on.
template <typename Accel>
void render_round(const RenderContext<Accel>& ctx, bool first_round, RoundDeadline& deadline,
                  RenderJournal& journal, RenderProgress* progress, RenderResult& result) {
  RenderState& state = journal.state();
  for (;;) {
    std::vector<std::size_t> list;
    for (std::size_t p = 0; p < state.targets.size(); ++p) {
      if (state.targets[p] > state.pixels.samples[p]) list.push_back(p);
    }
    if (list.empty()) return;
    // A save falls due only after a group has run, so the round moves however short the
    // interval.
    std::atomic<bool> moved_since_save{false};
    const std::function<bool()> may_skip = [&] {
      if ((moved_since_save.load() && journal.due()) || (!first_round && deadline())) return true;
      moved_since_save = true;
      return false;
    };
    result.rays_traced +=
        render_pixel_list(ctx, list, state.targets, state.pixels, progress, may_skip);
    if (deadline.ended() || !journal.due()) return;
    journal.save(result);
  }
}

// The least and the most samples a pixel of an error target takes (the least no more than the
// most).
struct CountRange {
  std::uint32_t least, most;
};
template <typename Target>
CountRange count_range(const Target& target) {
  const auto most = std::uint32_t(target.most);
  return {std::min(most, std::uint32_t(target.least)), most};
}

// Whether a round has anything to render: some pixel's target above its count.
inline bool any_target_above(const RenderState& state) {
  for (std::size_t p = 0; p < state.targets.size(); ++p) {
    if (state.targets[p] > state.pixels.samples[p]) return true;
  }
  return false;
}

// The targets a render starts from: the state's round under way, or every pixel at the
// minimum. Returns whether that is the first round (some pixel is below the minimum).
inline bool start_rounds(RenderState& state, std::uint32_t least) {
  if (state.targets.empty()) state.targets.assign(state.pixels.samples.size(), least);
  return std::any_of(state.pixels.samples.begin(), state.pixels.samples.end(),
                     [&](std::uint32_t n) { return n < least; });
}

// The count a --target-error pixel of count n goes to when its estimated relative variance
// of the mean `variance` is above the target's: what reaches the target if the variance falls
// as n^-rate, but at least n 2^(1/4) and at most 2n. Doubling alone left a pixel anywhere in
// [0.71, 1] of the target (median 0.70 of it on the cover); a rate below the sampler's only
// costs another look, since a pixel stops only once its estimate is at the target. (The
// judgement is its neighbours', so its own mean stays unbiased however many looks it gets.)
inline std::uint32_t next_target_count(std::uint32_t n, double variance, double target_variance,
                                       double rate, std::uint32_t most) {
  const double reaches = std::ceil(double(n) * std::pow(variance / target_variance, 1.0 / rate));
  const double least_step = std::ceil(double(n) * 1.189207115002721);  // 2^(1/4)
  const double next = std::max(least_step, std::min(2.0 * double(n), reaches));
  return std::uint32_t(std::min(double(most), next));
}

// --target-error: every pixel takes the minimum, then each round raises the samples of the
// pixels whose estimated relative standard error is still above the target (up to the
// maximum), by next_target_count.
template <typename Accel>
void render_adaptive(const RenderContext<Accel>& ctx, const PixelErrorTarget& target,
                     RenderProgress* progress, RenderJournal& journal, RenderResult& result) {
  const RenderSettings& settings = ctx.settings;
  RenderState& state = journal.state();
  PixelAccumulators& pixels = state.pixels;
  RoundDeadline deadline(settings, progress, journal);
  const auto [least, most] = count_range(target);
  const double target_variance = target.error * target.error;
  // How fast a pixel's variance falls with its count: 1/n for independent samples, about
  // n^-1.2 for the Sobol samplers (the cover's RMSE slope is -0.6, docs/accuracy.md).
  const double rate = settings.sampler == SamplerKind::Independent ? 1.0 : 1.2;
  std::vector<std::uint32_t>& targets = state.targets;
  // Each pixel's relative variance of its mean, as the sums stand.
  const auto judge = [&] {
    std::vector<double> judged = with_threads(settings.threads, [&] {
      return neighbourhood_relative_variance(settings, pixels, Pooling::Median);
    });
    for (std::size_t p = 0; p < judged.size(); ++p) judged[p] /= double(pixels.samples[p]);
    return judged;
  };
  // Every round is judged, and the render ends when a judgement asks for nothing more: a
  // render resumed from a save taken as a round ended is judged as the uninterrupted one was.
  for (bool first = start_rounds(state, least);; first = false) {
    render_round(ctx, first, deadline, journal, progress, result);
    if (deadline.ended()) break;
    const std::vector<double> judged = judge();
    result.pixels_above_target = 0;
    std::int64_t above = 0;  // for a progress display: pixels short of the target, capped or not
    for (std::size_t p = 0; p < targets.size(); ++p) {
      const std::uint32_t n = pixels.samples[p];
      if (judged[p] <= target_variance) continue;
      ++above;
      if (n < most)
        targets[p] = next_target_count(n, judged[p], target_variance, rate, most);
      else
        ++result.pixels_above_target;  // at the cap, short of the target
    }
    progress->pixels_above_target = above;
    ++progress->judgements;
    if (!any_target_above(state)) break;
  }
  // Ended in a round (its time limit, a stop): the pixels still above the target are counted on
  // the sums it ends with, capped or not; the last judgement counted only those at the cap, and
  // the summary claimed a target that most pixels had not reached.
  if (deadline.ended()) {
    const std::vector<double> judged = judge();
    std::uint64_t above = 0;
    for (const double variance : judged) above += variance > target_variance ? 1 : 0;
    result.pixels_above_target = above;
    progress->pixels_above_target = std::int64_t(above);
  }
  deadline.report(result, pixels);
}

// --image-error E stops where the estimated error is this fraction of E. The estimate is
// calibrated to a few percent, not exactly: rounds on the cover stopped at 0.98-1.03 E when they
// aimed at E (docs/accuracy.md), and a user who asks for E expects no more than E.
inline constexpr double kImageErrorAim = 0.92;

// --image-error and --adaptive: after the minimum, each round allocates counts proportional to
// sqrt(v / c) (sample_allocation.h). With an image error, until the estimated mean relMSE is
// the error squared, each pixel at most doubling per round. With a budget (the cost of --spp
// uniform samples, estimated from the pooled costs, and/or the time limit), rounds double the
// cost spent so far, so the estimates are refined about log2(budget / first round) times.
template <typename Accel>
void render_by_image_error(const RenderContext<Accel>& ctx, RenderProgress* progress,
                           RenderJournal& journal, RenderResult& result) {
  const RenderSettings& settings = ctx.settings;
  RenderState& state = journal.state();
  PixelAccumulators& pixels = state.pixels;
  RoundDeadline deadline(settings, progress, journal);
  const auto* by_error = std::get_if<ImageErrorTarget>(&settings.samples);
  const auto* by_budget = std::get_if<AdaptiveBudget>(&settings.samples);
  // The uniform samples per pixel whose cost is the budget (infinite: the time limit's).
  const double budget_spp =
      by_budget && by_budget->per_pixel ? double(*by_budget->per_pixel) : INFINITY;
  const std::uint32_t most =
      by_error ? std::uint32_t(by_error->most) : limits::kMostAdaptiveSamples;
  std::uint32_t least =
      std::min(most, std::uint32_t(by_error ? by_error->least : by_budget->least));
  if (budget_spp < double(least)) least = std::uint32_t(budget_spp);
  for (bool first = start_rounds(state, least);; first = false) {
    render_round(ctx, first, deadline, journal, progress, result);
    // After the round that spends the rest of the budget a judgement could only end the render.
    if (deadline.ended() || state.last_round) break;
    const PixelEstimates e =
        with_threads(settings.threads, [&] { return pooled_estimates(settings, pixels); });
    if (by_error) {
      const double aim = kImageErrorAim * by_error->error;
      const double goal = aim * aim;
      const double estimate = estimated_rel_mse(e.variance, pixels.samples);
      result.estimated_image_error = std::sqrt(estimate);
      progress->image_error = result.estimated_image_error;
      ++progress->judgements;
      if (estimate <= goal) break;
      state.targets = with_threads(
          settings.threads, [&] { return allocate_for_error(e, pixels.samples, goal, most); });
      for (std::size_t p = 0; p < state.targets.size(); ++p) {
        state.targets[p] = std::min(state.targets[p], 2 * pixels.samples[p]);
      }
      if (!any_target_above(state)) break;  // every pixel at the cap
      continue;
    }
    const double spent = estimated_cost(e.cost, pixels.samples);
    // The budget: what every pixel at the budget's count would cost.
    double budget = std::isinf(budget_spp)
                        ? INFINITY
                        : budget_spp * std::accumulate(e.cost.begin(), e.cost.end(), 0.0);
    if (settings.time_limit_seconds > 0.0) {
      // What the time left holds at the rate so far (timing decides only when rounds end).
      const double rate = double(result.rays_traced) / std::max(deadline.elapsed(), 1e-9);
      budget = std::min(budget, spent + rate * (settings.time_limit_seconds - deadline.elapsed()));
    }
    progress->budget_rays = budget, progress->spent_rays = spent;
    progress->rays_at_judgement = progress->rays_traced.load();
    ++progress->judgements;
    if (!(budget > spent)) break;
    state.last_round = 2.0 * spent >= budget;
    state.targets = with_threads(settings.threads, [&] {
      return allocate_budget(e, pixels.samples, std::min(budget, 2.0 * spent), most);
    });
    if (!any_target_above(state)) break;
  }
  // Ended between judgements (its time limit, a stop): the last judgement saw fewer samples than
  // the image has, so the image's estimate is taken from its final sums, as a judgement would.
  if (by_error && deadline.ended()) {
    const PixelEstimates e =
        with_threads(settings.threads, [&] { return pooled_estimates(settings, pixels); });
    result.estimated_image_error = std::sqrt(estimated_rel_mse(e.variance, pixels.samples));
    progress->image_error = result.estimated_image_error;
  }
  deadline.report(result, pixels);
}

}  // namespace rtiow
