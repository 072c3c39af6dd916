#pragma once
// A render's checkpoint as the command line keeps it: beside the output
// (<output>.rtiow-checkpoint), read to --resume, refreshed every --checkpoint seconds and when
// the render ends (finished or stopped), kept after it (so a finished render can be refined
// with more samples). A save that fails while the render runs warns once and the render goes
// on; the last save's failure is told with the render's outcome, and if the checkpoint's own
// place cannot take the render's end, it is kept in $TMPDIR (or /tmp) instead.

#include <optional>
#include <string>

#include "core/render/checkpoint_file.h"
#include "core/render/render.h"
#include "core/render/render_state.h"
#include "core/scene/scene.h"

namespace rtiow {

class CheckpointSession {
 public:
  // `interval_seconds` 0 turns checkpoints off. With `resume`, reads the checkpoint (throws
  // InvalidInput if it is not one of this request); without one, the render starts afresh
  // and says so.
  CheckpointSession(const std::string& output, const Scene& scene, const RenderSettings& settings,
                    double interval_seconds, bool resume, bool quiet);

  // What to hand to render(): nothing when checkpoints are off and there is nothing to resume.
  const Checkpointing* checkpointing() const {
    return enabled_ || resumed_ ? &checkpointing_ : nullptr;
  }

  const std::string& path() const { return path_; }
  bool enabled() const { return enabled_; }
  // Whether the last save succeeded, so a checkpoint holds where the render ended: at path(),
  // or, when the render's end could not be saved there, in the temporary directory.
  bool holds_the_render() const { return enabled_ && last_save_ok_; }
  const std::string& kept_at() const { return kept_at_; }
  // What to do with the kept checkpoint to get the image ("run the same command with --resume").
  std::string how_to_continue() const;
  // Why the last save failed (empty if it did not).
  const std::string& failure() const { return failure_; }
  // The samples per pixel the resumed checkpoint held (the most, when adaptive).
  std::optional<std::uint32_t> resumed_from() const { return resumed_from_; }

 private:
  void save(const RenderState& state, bool ended);

  std::string path_;
  CheckpointIdentity identity_;
  bool enabled_ = false;
  bool last_save_ok_ = false;
  bool warned_ = false;
  std::string failure_;
  std::string kept_at_;
  std::optional<RenderState> resumed_;
  std::optional<std::uint32_t> resumed_from_;
  Checkpointing checkpointing_;
};

}  // namespace rtiow
