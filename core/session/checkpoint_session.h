#pragma once
// A render's checkpoint as the command line keeps it: beside the output
// (<output>.rtiow-checkpoint), refreshed every --checkpoint seconds while the render runs, so a
// kill loses at most that much work, and read by --resume.
//
// When the render ends:
// - stopped by a signal: the state is saved, to be continued with --resume;
// - finished (its samples done, or its time limit reached) and the image written: the
//   checkpoint is removed, so the directory holds what the user asked for, unless
//   --keep-state asked to keep it for refining (a larger --spp with --resume);
// - the image could not be written: the state is saved, and the error says where.
// A save that fails while the render runs warns once and the render goes on; if the
// checkpoint's own place cannot take the render's end, it is kept in $TMPDIR (or /tmp) under
// an unpredictable name instead, and a warning says so (-q never hides where work is kept).
//
// A checkpoint already beside the output is never replaced silently: without --resume (to
// continue it) or --restart (to discard it), the render is refused, naming what the
// checkpoint holds.

#include <cstdint>
#include <optional>
#include <string>

#include "core/render/checkpoint_file.h"
#include "core/render/render.h"
#include "core/render/render_state.h"
#include "core/scene/scene.h"

namespace rtiow {

struct CheckpointOptions {
  double interval_seconds = 60.0;  // 0: no checkpoint while the render runs
  bool resume = false;             // continue the checkpoint beside the output
  bool restart = false;            // discard it
  bool keep_state = false;         // keep the state of a finished render, to refine it
  bool quiet = false;
};

class CheckpointSession {
 public:
  // Throws InvalidInput if the checkpoint is not one of this request (with resume), or if one
  // is there and neither resume nor restart says what to do with it.
  CheckpointSession(const std::string& output, const Scene& scene, const RenderSettings& settings,
                    const CheckpointOptions& options);

  // What to hand to render(): nothing when no state is read or kept.
  const Checkpointing* checkpointing() const { return uses_state() ? &checkpointing_ : nullptr; }

  const std::string& path() const { return path_; }
  // The samples per pixel the resumed checkpoint held (the most, when adaptive).
  std::optional<std::uint32_t> resumed_from() const { return resumed_from_; }

  // After the image is written: removes the checkpoint unless the state is to be kept.
  void image_written();
  // After the image could not be written: keeps `state` (saved now if the render's end was not).
  void image_lost(const RenderState& state);

  // Whether the render's state is kept (after image_lost, or a stop), and where.
  bool holds_the_render() const { return !kept_at_.empty(); }
  const std::string& kept_at() const { return kept_at_; }
  // What to do with the kept checkpoint ("run the same command with --resume").
  std::string how_to_continue() const;
  // Why the last save failed (empty if it did not).
  const std::string& failure() const { return failure_; }
  // Warnings about where the state is (a fallback, a stale file), printed even when quiet.
  void warn_where_kept() const;

 private:
  bool uses_state() const { return options_.interval_seconds > 0.0 || resumed_.has_value(); }
  void refuse_unless_told();
  void save(const RenderState& state, SaveReason reason);
  bool save_to(const std::string& path, const RenderState& state);

  std::string path_;
  CheckpointOptions options_;
  RenderIdentity identity_;
  bool wrote_beside_ = false;  // a checkpoint of this render is (or was) at path_
  bool warned_ = false;
  bool finished_ = false;
  std::string failure_;
  std::string kept_at_;
  std::optional<RenderState> resumed_;
  std::optional<std::uint32_t> resumed_from_;
  Checkpointing checkpointing_;
};

}  // namespace rtiow
