#pragma once
// A render as a program runs it, with what goes around it, for the command line and any other
// caller of the library alike (as pbrt-v4's render loop owns its display server and partial
// images): the output and its checkpoint claimed for the whole session
// (core/io/output_claim.h); the checkpoint continued, refused or discarded as asked, saved as the
// render goes and removed or kept at its end (checkpoint_session.h); the output replaced by
// previews (render_preview.h) and the render shown in tev (tev_display.h); and its end: the
// image written, or, for a render stopped short over an image that was there before it, that
// image left as it was and the samples kept in the checkpoint or beside it (issue 69).
//
// Signals, progress lines and summaries are the caller's: a stop is asked through the
// RenderProgress handed to render(), and deliver() is the final write a second signal should
// wait for.

#include <memory>
#include <optional>
#include <string>

#include "core/io/output_claim.h"
#include "core/render/render_job.h"
#include "core/render/render_state.h"
#include "core/session/checkpoint_session.h"
#include "core/session/render_preview.h"
#include "core/session/tev_display.h"

namespace rtiow {

struct SessionOptions {
  // This process writes the output (under MPI, rank 0 alone): it claims the output and its
  // checkpoint, and loads the image library while the render runs.
  bool writes_output = true;
  // The render keeps a checkpoint beside its output, as `checkpoint` says (none for a share of
  // a distributed render, whose ranks hold only their own samples).
  bool checkpointed = true;
  CheckpointOptions checkpoint;
  double preview_seconds = 0.0;           // 0: no previews of the output
  std::optional<DisplayAddress> display;  // the tev viewer, if any
  bool reproducible = false;              // the image's metadata without the time or the host
};

// Refuses options that contradict each other (resume and restart; keep_state without a
// checkpoint), in the caller's words; RenderSession's constructor checks them too.
void check_session_options(const SessionOptions& options);

// How a session's render ended up on disk, for whoever reports it.
struct SessionEnd {
  std::string written;     // where the image went (empty: its samples are in the checkpoint)
  std::string left_alone;  // an image that was at the output before, left as it was
  bool kept_in_checkpoint = false;
  std::optional<DenoiseFigures> denoised;       // what the denoiser delivered (--denoise)
  std::optional<DenoisedImage> denoised_image;  // and the image it made, with its estimates
};

class RenderSession {
 public:
  // Claims, opens the checkpoint, starts the viewer's connection: throws InvalidInput (a
  // checkpoint of another render, a claim refused) before any work.
  RenderSession(RenderJob& job, const JobRequest& request, const SessionOptions& options);
  ~RenderSession();
  RenderSession(const RenderSession&) = delete;
  RenderSession& operator=(const RenderSession&) = delete;

  // Renders the job (continuing the checkpoint where one is resumed), saving, previewing and
  // showing it at its safe points.
  RenderResult render(RenderProgress& progress);

  // The final write: shows the result, then writes the image, or keeps a stopped render's
  // samples without replacing what was at the output (in the checkpoint, else in
  // partial_output_path()). If the image cannot be written, the render's state is kept and the
  // error (std::runtime_error) says where. The denoiser's progress goes to `denoising`, where
  // given (a display shows it). A denoised error target that ended between judgements takes
  // its estimate from the image denoised for the output (take_delivered_estimate()), before the
  // metadata reports it.
  SessionEnd deliver(RenderResult& result, WorkProgress* denoising = nullptr);

  // Gives the viewer its last picture (at most kViewerSeconds; none once `stop` is set).
  void let_viewer_finish(const std::atomic<bool>& stop);

  // The checkpoint, if the session keeps one: where the render is kept and how to continue it.
  const CheckpointSession* checkpoint() const { return checkpoint_.get(); }
  // Temporaries an interrupted rtiow had left beside the output, removed by the claims.
  int removed_temporaries() const { return removed_temporaries_; }

 private:
  std::optional<DenoisedImage> write_or_keep(RenderResult& result, WorkProgress* denoising);

  RenderJob& job_;
  const JobRequest& request_;
  SessionOptions options_;
  bool output_was_there_ = false;
  std::optional<OutputClaim> image_claim_, checkpoint_claim_, partial_claim_;
  int removed_temporaries_ = 0;
  std::unique_ptr<CheckpointSession> checkpoint_;
  std::unique_ptr<TevDisplay> display_;
  std::unique_ptr<RenderPreview> preview_;
  std::optional<Checkpointing> watched_;  // the checkpoint's saves with previews added
};

}  // namespace rtiow
