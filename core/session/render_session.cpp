#include "core/session/render_session.h"

#include <exception>
#include <filesystem>
#include <new>
#include <stdexcept>
#include <system_error>

#include "core/io/image_backend.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/limits/setting_name.h"
#include "core/render/denoised_output.h"
#include "core/render/first_hit_passes.h"
#include "core/render/render.h"
#include "core/render/render_metadata.h"

namespace rtiow {

void check_session_options(const SessionOptions& options) {
  const CheckpointOptions& c = options.checkpoint;
  if (c.resume && c.restart) {
    throw InvalidInput("give " + setting("resume") + " or " + setting("restart") + ", not both");
  }
  if (c.keep_state && c.interval_seconds <= 0.0) {
    throw InvalidInput(setting("keep_state") + " keeps the render's checkpoint: it needs " +
                       setting("checkpoint") + " above 0");
  }
}

RenderSession::RenderSession(RenderJob& job, const JobRequest& request,
                             const SessionOptions& options)
    : job_(job), request_(request), options_(options) {
  check_session_options(options_);
  // Previews and the viewer show a whole render; a part file is a share of one.
  for (const auto& [watching, name] : {std::pair{options_.preview_seconds > 0.0, "preview"},
                                       std::pair{!!options_.display, "display"}}) {
    if (watching && job_.share) {
      throw InvalidInput(setting(name) + " shows a whole render; a part file (" + setting("part") +
                         ", " + setting("sample_range") + ") is a share of one");
    }
  }
  if (options_.writes_output) {
    // Whether the output holds a file already, before anything of this session writes it: a
    // render stopped short never replaces it.
    std::error_code absent;
    output_was_there_ =
        std::filesystem::exists(std::filesystem::symlink_status(job_.output, absent));
    image_claim_.emplace(job_.output);
    checkpoint_claim_.emplace(checkpoint_path(job_.output));
    removed_temporaries_ =
        image_claim_->removed_temporaries() + checkpoint_claim_->removed_temporaries();
  }
  if (options_.checkpointed) {
    checkpoint_ = std::make_unique<CheckpointSession>(job_.output, job_.scene, job_.settings,
                                                      options_.checkpoint);
  }
  if (options_.display) {  // the image in tev, from its first pass to its end
    display_ = std::make_unique<TevDisplay>(
        *options_.display, std::filesystem::path(job_.output).filename().string(),
        film_width(job_.settings), film_height(job_.settings), frame_placement(job_.settings),
        pass_channel_names(job_.settings.passes));
  }
  // Previews at the checkpoints' safe points between passes (the viewer's every second unless
  // previews of the file say otherwise).
  const bool to_file = options_.preview_seconds > 0.0;
  preview_ = std::make_unique<RenderPreview>(job_, to_file, display_.get());
  if (to_file || display_) {
    watched_ = preview_->watching(checkpoint_ ? checkpoint_->checkpointing() : nullptr,
                                  to_file ? options_.preview_seconds : 1.0);
  }
}

RenderSession::~RenderSession() = default;

RenderResult RenderSession::render(RenderProgress& progress) {
  // The image library loads on a second thread while the render runs, unless rtiow encodes the
  // format itself (PNG): then it is never loaded.
  if (options_.writes_output) {
    start_parallel_runtime();
    const ImageFormat* format = image_format(job_.output);
    if (!format || !format->own_encoder) preload_image_backend();
  }
  const Checkpointing* checkpointing = watched_      ? &*watched_
                                       : checkpoint_ ? checkpoint_->checkpointing()
                                                     : nullptr;
  return rtiow::render(job_.scene, job_.settings, &progress, checkpointing);
}

SessionEnd RenderSession::deliver(RenderResult& result, WorkProgress* denoising) {
  if (display_) display_->show(result.film, pass_channels(result, job_.settings.passes));
  // A stopped render leaves a file that was there before it (and that no preview of its own
  // replaced) as it was: its samples are in the checkpoint, or else in a file beside it.
  SessionEnd end;
  const std::string asked = job_.output;
  const bool keep_what_was_there = result.stopped && output_was_there_ && !preview_->wrote_output();
  end.kept_in_checkpoint = keep_what_was_there && checkpoint_ && checkpoint_->holds_the_render();
  if (keep_what_was_there) end.left_alone = asked;
  if (end.kept_in_checkpoint) return end;
  if (keep_what_was_there) {
    job_.output = partial_output_path(asked);
    check_output_path(job_.output, {asked});
    partial_claim_.emplace(job_.output);
  }
  end.denoised_image = write_or_keep(result, denoising);
  if (end.denoised_image) {
    end.denoised = figures_of(*end.denoised_image);
    // The viewer's last picture is the image written: the noisy one went out above, before the
    // denoiser's time, and the denoised one follows it.
    if (display_)
      display_->show(end.denoised_image->image, pass_channels(result, job_.settings.passes));
  }
  end.written = job_.output;
  return end;
}

// Writes the image; if that fails after the render, keeps the render's state and says where.
std::optional<DenoisedImage> RenderSession::write_or_keep(RenderResult& result,
                                                          WorkProgress* denoising) {
  CheckpointSession* checkpoint = checkpoint_.get();
  std::optional<DenoisedImage> denoised;
  try {
    denoised = denoise_for_output(request_, job_, result, denoising);
    if (denoised) take_delivered_estimate(job_.settings, result, *denoised);
    Metadata metadata = render_metadata(job_.scene, job_.settings, result, options_.reproducible);
    if (!request_.scene_file.empty()) {
      metadata.emplace_back(metadata_key::kSceneFile, request_.scene_file);
    }
    write_job_result(request_, job_, result, metadata, denoised ? &*denoised : nullptr);
  } catch (const InvalidInput&) {
    throw;
  } catch (const std::exception& e) {
    if (!checkpoint || !checkpoint->checkpointing()) throw;  // no checkpoint: nothing kept
    const std::string what = dynamic_cast<const std::bad_alloc*>(&e)
                                 ? "out of memory writing " + quote_value(job_.output, kWholePath)
                                 : std::string(e.what());
    // The denoised image's planes are no longer wanted; the state is lent, not copied: the
    // write may have failed for want of memory.
    denoised.reset();
    RenderState state = take_state(result);
    try {
      checkpoint->image_lost(state);
    } catch (const std::bad_alloc&) {  // no memory to save it: said below
    }
    restore_state(std::move(state), result);
    if (!checkpoint->holds_the_render()) {
      throw std::runtime_error(
          what + "; and the render's state could not be kept" +
          (checkpoint->failure().empty() ? std::string() : " (" + checkpoint->failure() + ")"));
    }
    throw std::runtime_error(what + "; the render is kept in " +
                             quote_value(checkpoint->kept_at(), kWholePath) + ": " +
                             checkpoint->how_to_continue() + " to write it");
  }
  if (checkpoint) checkpoint->image_written();
  return denoised;
}

void RenderSession::let_viewer_finish(const std::atomic<bool>& stop) {
  if (display_) display_->finish(stop);
}

}  // namespace rtiow
