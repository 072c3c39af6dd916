#pragma once
// `rtiow render --preview SECONDS`: while the render runs, its output is replaced every
// SECONDS by an image of the samples so far, so any viewer that reloads the file watches it.
// Each preview goes through the output's claim like the final image (an exclusive temporary
// renamed into place), carries the render's metadata with `rtiow:preview` saying how far it
// is, and is written between passes, where the state is whole; the finished file is the one a
// render without --preview writes. A preview that cannot be written warns once and the render
// goes on.

#include <string>

#include "core/render/render_job.h"
#include "core/render/render_state.h"

namespace rtiow {

class TevDisplay;

class RenderPreview {
 public:
  // Replaces the output if `to_file`; shows the image on `display` if there is one (--display).
  RenderPreview(const RenderJob& job, bool to_file, TevDisplay* display)
      : job_(job), to_file_(to_file), display_(display) {}

  // `base` (a checkpoint's saving and resume, or none) with previews every `seconds` added.
  Checkpointing watching(const Checkpointing* base, double seconds);

  // Replaces the output with `state`'s image, and shows it.
  void write(const RenderState& state);

  // Whether a preview has replaced the output: what was there before is gone already.
  bool wrote_output() const { return wrote_output_; }

 private:
  const RenderJob& job_;
  bool to_file_;
  TevDisplay* display_;
  bool warned_ = false;
  bool wrote_output_ = false;
};

}  // namespace rtiow
