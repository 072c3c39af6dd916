#pragma once
// What a render has done so far, and how it is kept: enough to continue a render that was
// stopped, killed or finished to the bits an uninterrupted render gives. Pixel sums are
// exact and every decision between passes and rounds is a function of this state, so a
// render continued from it takes the same samples into the same sums
// (core/render/checkpoint_file.h keeps it on disk).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/render/pixel_accumulators.h"
#include "core/render/stopwatch.h"

namespace rtiow {

struct RenderState {
  PixelAccumulators pixels;
  // Adaptive sampling: each pixel's target in the round under way (empty before the first).
  // A round brings every pixel below its target up to it, so a round cut short continues
  // from these.
  std::vector<std::uint32_t> targets;
  bool last_round = false;        // --adaptive: the round under way spends the rest of the budget
  std::uint64_t rays_traced = 0;  // over the whole render so far
  double render_seconds = 0.0;    // spent so far: a time limit counts it
  double judging_seconds = 0.0;   // of it, the denoiser's judgements between rounds
  // Where an error-driven render stands (as in RenderResult).
  double estimated_image_error = 0.0;
  std::uint64_t pixels_above_target = 0;

  explicit RenderState(std::size_t pixel_count, bool keep_first_hits = false)
      : pixels(pixel_count, keep_first_hits) {}
};

// Why a state is saved: on the way, or because the render ended, stopped by a request (to be
// resumed) or finished (its work done, or its time limit reached: kept only to refine).
enum class SaveReason { Periodic, Stopped, Finished };

// How a render keeps its state. `save` is called between passes (or in the middle of an
// adaptive round) once `interval_seconds` have passed since the last save, and once more when
// the render ends. A render given `resume` continues from it (moved from). `preview`, a look
// at the render as it goes (--preview), is called at the same safe points once
// `preview_seconds` have passed since the last; never at the end, which the caller writes.
// Neither changes the image: a pixel's sum does not depend on where passes or rounds pause.
struct Checkpointing {
  RenderState* resume = nullptr;
  double interval_seconds = 0.0;  // 0: only when the render ends
  std::function<void(const RenderState& state, SaveReason reason)> save;
  double preview_seconds = 0.0;  // 0: no preview
  std::function<void(const RenderState& state)> preview;
};

// The render loops' side of checkpointing: the state they add to, when a save is due, and
// the time spent including what the state had before.
class RenderJournal {
 public:
  RenderJournal(RenderState& state, const Checkpointing* checkpointing)
      : state_(state),
        checkpointing_(checkpointing && (checkpointing->save || checkpointing->preview)
                           ? checkpointing
                           : nullptr),
        earlier_seconds_(state.render_seconds),
        start_(Clock::now()),
        last_save_(start_),
        last_preview_(start_) {}

  RenderState& state() { return state_; }

  // Seconds spent on the render, by this process and before it.
  double elapsed() const { return earlier_seconds_ + seconds_since(start_); }

  // Whether a periodic save or a preview is due (read by the render's tasks, so it only
  // reads).
  bool due() const { return save_due() || preview_due(); }

  // Saves the state with what `result` has counted (rays, where the error stands): a periodic
  // call saves and previews what is due, the render's end saves.
  template <typename Result>
  void save(const Result& result, SaveReason reason = SaveReason::Periodic) {
    if (!checkpointing_) return;
    state_.rays_traced = result.rays_traced;
    state_.estimated_image_error = result.estimated_image_error;
    state_.pixels_above_target = result.pixels_above_target;
    state_.render_seconds = elapsed();
    state_.judging_seconds = result.judging_seconds;
    if (reason == SaveReason::Periodic && preview_due()) {
      checkpointing_->preview(state_);
      last_preview_ = Clock::now();
    }
    if (checkpointing_->save && (reason != SaveReason::Periodic || save_due())) {
      checkpointing_->save(state_, reason);
      last_save_ = Clock::now();
    }
  }

 private:
  bool save_due() const {
    return checkpointing_ && checkpointing_->save && checkpointing_->interval_seconds > 0.0 &&
           seconds_since(last_save_) >= checkpointing_->interval_seconds;
  }
  bool preview_due() const {
    return checkpointing_ && checkpointing_->preview && checkpointing_->preview_seconds > 0.0 &&
           seconds_since(last_preview_) >= checkpointing_->preview_seconds;
  }

  RenderState& state_;
  const Checkpointing* checkpointing_;
  double earlier_seconds_;
  Clock::time_point start_, last_save_, last_preview_;
};

}  // namespace rtiow
