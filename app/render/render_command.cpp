#include "app/render/render_command.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "app/interrupt.h"
#include "app/mpi_session.h"
#include "app/progress_display.h"
#include "app/render/checkpoint_session.h"
#include "app/render/image_request.h"
#include "app/render/render_options.h"
#include "app/render/render_preview.h"
#include "app/render/render_summary.h"
#include "core/io/atomic_file.h"
#include "core/io/image_backend.h"
#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"
#include "core/parallel/cancellation.h"
#include "core/parallel/thread_count.h"
#include "core/render/first_hit_passes.h"
#include "core/render/render_job.h"
#include "core/render/render_metadata.h"
#include "core/render/render_outcome.h"
#include "core/render/render_statistics.h"
#include "core/render/sample_share.h"
#include "core/session/tev_display.h"
#include "core/scene/builtin_scenes.h"

namespace rtiow {
namespace {

int list_scenes() {
  for (const auto& s : builtin_scenes())
    std::printf("%-16s %s\n", s.name.c_str(), s.summary.c_str());
  return 0;
}

// Renders with, unless quiet, a progress display (under MPI on rank 0's share, which moves with
// the others').
RenderResult render_with_progress(const RenderOptions& o, const RenderJob& job,
                                  const MpiSession& mpi, RenderProgress& progress,
                                  const Checkpointing* checkpointing) {
  std::unique_ptr<ProgressDisplay> display;
  if (!o.quiet && mpi.rank() == 0) {
    display = std::make_unique<ProgressDisplay>(progress, job.settings);
  }
  return render(job.scene, job.settings, &progress, checkpointing);
}

// Under MPI, rank 0 adds every rank's exact sums into the image of one process with all the
// samples; false on the other ranks, which are done. The spreads travel too (they triple what
// a rank sends, once, at the end): the image's error estimate needs them, and the file is the
// single process's, byte for byte.
bool gather_ranks(const MpiSession& mpi, RenderJob& job, RenderResult& result) {
  const std::uint64_t done = mpi.reduce_sum(std::uint64_t(result.samples_completed));
  result.rays_traced = mpi.reduce_sum(result.rays_traced);
  result.render_seconds = mpi.reduce_max(result.render_seconds);
  mpi.reduce_sums(result.sums);
  if (mpi.rank() != 0) return false;
  result.stopped = done < job.samples_asked;
  complete_from_shares(done, result);
  // The estimate of the whole image, from every rank's sums (each rank's was of its share).
  const ImageErrorEstimate estimate = estimate_image_error(result, job.settings.threads);
  result.estimated_image_error = estimate.error, result.error_estimate = estimate.kind;
  restore_whole_job(job.samples_asked, job.settings);
  return true;
}

// "rendered cover 1200x800, 500 spp, depth 50, embree, 2 threads: ... -> path"
void print_summary(const RenderJob& job, const RenderResult& result, const MpiSession& mpi) {
  const RenderSettings& s = job.settings;
  const double rays = double(result.rays_traced);
  const int threads = thread_count(s.threads);  // the threads used (core/parallel/thread_count.h)
  const std::string ranks = mpi.distributed() ? std::to_string(mpi.size()) + " ranks x " : "";
  const RenderOutcome outcome = describe_outcome(s, result);
  std::fprintf(stderr,
               "rendered %s %dx%d%s, %s%s, depth %d, %s, %s%d thread%s: %.2f s, %.3g rays, "
               "%.2f Mrays/s -> %s\n",
               job.scene.name.c_str(), s.width, s.height,
               s.crop ? (" crop " + to_string(*s.crop)).c_str() : "", outcome.samples.c_str(),
               outcome.error.empty() ? "" : (", " + outcome.error).c_str(), s.max_depth,
               to_string(s.accel).c_str(), ranks.c_str(), threads, threads == 1 ? "" : "s",
               result.render_seconds, rays, rays / result.render_seconds * 1e-6,
               one_line(job.output).c_str());
}

// The checkpoint of this process's render: none under mpirun (each rank holds only its
// share), where --resume is refused.
std::unique_ptr<CheckpointSession> open_checkpoint(const RenderOptions& o, const RenderJob& job,
                                                   const MpiSession& mpi) {
  if (mpi.distributed()) {
    if (o.resume) throw InvalidInput("--resume is for a render in one process, not under mpirun");
    return nullptr;
  }
  if (o.resume && o.restart) throw InvalidInput("give --resume or --restart, not both");
  CheckpointOptions options;
  options.interval_seconds = o.checkpoint_seconds;
  options.resume = o.resume, options.restart = o.restart;
  options.keep_state = o.keep_state, options.quiet = o.quiet;
  if (o.keep_state && o.checkpoint_seconds <= 0.0) {
    throw InvalidInput("--keep-state keeps the render's checkpoint: it needs --checkpoint above 0");
  }
  auto session = std::make_unique<CheckpointSession>(job.output, job.scene, job.settings, options);
  if (session->resumed_from() && !o.quiet) {
    std::fprintf(stderr, "rtiow: resuming from %s (%u spp done)\n",
                 quote_value(session->path()).c_str(), *session->resumed_from());
  }
  return session;
}

// Writes the image; if that fails after the render, keeps the render's state and says where.
void write_or_keep(const RenderOptions& o, const JobRequest& request, const RenderJob& job,
                   const RenderResult& result, CheckpointSession* checkpoint) {
  try {
    Metadata metadata = render_metadata(job.scene, job.settings, result, o.reproducible);
    if (!request.scene_file.empty()) {
      metadata.emplace_back(metadata_key::kSceneFile, request.scene_file);
    }
    write_job_result(request, job, result, metadata);
  } catch (const InvalidInput&) {
    throw;
  } catch (const std::exception& e) {
    if (!checkpoint || !checkpoint->checkpointing()) throw;  // --checkpoint 0: nothing kept
    const std::string what = dynamic_cast<const std::bad_alloc*>(&e)
                                 ? "out of memory writing " + quote_value(job.output, kWholePath)
                                 : std::string(e.what());
    try {
      checkpoint->image_lost(state_of(result));
    } catch (const std::bad_alloc&) {  // no memory for a copy of the state: said below
    }
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
}

// A uniform render that asks for more than a day of work on a 2-core machine (the cover runs
// at about 5e6 samples per second there) says so before it starts, and how to bound it: the
// count is accepted (a farm or a long night may mean it), but not silently.
void note_long_request(const RenderJob& job) {
  const RenderSettings& s = job.settings;
  const std::optional<std::uint64_t> total = uniform_total_samples(s);
  if (!total || s.time_limit_seconds > 0) return;
  const double samples = double(*total);
  constexpr double kSamplesPerSecond = 5e6, kDay = 86400;
  const double days = samples / kSamplesPerSecond / kDay;
  if (days < 1) return;
  std::fprintf(stderr,
               "rtiow: note: %d spp at %dx%d is %.3g samples, about %.3g days on a 2-core machine; "
               "a signal (Ctrl-C) keeps what is done and --resume continues it, --time-limit "
               "bounds it\n",
               *spp_option(s.samples), film_width(s), film_height(s), samples, days);
}

// A signal that arrived where the render could not stop for it (the scene's load, the final
// writes) ends the command once they are done, in rtiow's words; 0 if none did.
int interrupted_outside_render(const char* when) {
  const int signal = InterruptGuard::signal_received();
  if (signal == 0) return 0;
  std::fprintf(stderr, "rtiow: interrupted (signal %d) %s\n", signal, when);
  return 128 + signal;
}

// The output and its checkpoint, claimed for the whole command (core/io/output_claim.h); what
// an interrupted rtiow left beside them is removed, and said.
struct ClaimedOutputs {
  ClaimedOutputs(const std::string& output, const std::string& summary, bool quiet)
      : image(output), checkpoint(checkpoint_path(output)) {
    if (!summary.empty()) summary_json.emplace(summary);
    const int removed = image.removed_temporaries() + checkpoint.removed_temporaries();
    if (removed > 0 && !quiet) {
      std::fprintf(stderr, "rtiow: removed %d temporar%s an interrupted rtiow left beside %s\n",
                   removed, removed == 1 ? "y" : "ies", quote_value(output).c_str());
    }
  }
  OutputClaim image, checkpoint;
  std::optional<OutputClaim> summary_json;  // --summary-json
};

// "rtiow: interrupted: wrote 37 spp (of 100 asked) to cover.png; the render is kept in ...",
// or, where `left_alone` names a file that was there before this render, "... kept in
// 'cover.png.rtiow-checkpoint' (...); 'cover.png', which this render did not finish, is left as
// it was" (`only_in_checkpoint`), or "wrote ... to cover.partial.png; 'cover.png' ... ".
int report_interrupted(const RenderJob& job, const RenderResult& result,
                       const CheckpointSession* checkpoint, const std::string& left_alone,
                       bool only_in_checkpoint) {
  const RenderOutcome outcome = describe_outcome(job.settings, result);
  const std::string continued = checkpoint && checkpoint->holds_the_render()
                                    ? quote_value(checkpoint->kept_at(), kWholePath) + " (" +
                                          checkpoint->how_to_continue() + " to continue it)"
                                    : "";
  const std::string untouched = left_alone.empty()
                                    ? ""
                                    : "; " + quote_value(left_alone, kWholePath) +
                                          ", which this render did not finish, is left as it was";
  if (only_in_checkpoint) {
    std::fprintf(stderr, "rtiow: interrupted: %s%s kept in %s%s\n", outcome.samples.c_str(),
                 outcome.asked.c_str(), continued.c_str(), untouched.c_str());
  } else {
    std::fprintf(stderr, "rtiow: interrupted: wrote %s%s to %s%s%s\n", outcome.samples.c_str(),
                 outcome.asked.c_str(), one_line(job.output).c_str(),
                 continued.empty() ? "" : ("; the render is kept in " + continued).c_str(),
                 untouched.c_str());
  }
  return 128 + InterruptGuard::signal_received();
}

int run_render(const RenderOptions& o, const JobRequest& request, const MpiSession& mpi) {
  if (o.list_scenes) return mpi.rank() == 0 ? list_scenes() : 0;
  if (!o.summary_json.empty()) {
    std::vector<std::string> inputs;
    for (const std::string* input : {&request.scene_file, &o.like}) {
      if (!input->empty()) inputs.push_back(*input);
    }
    check_output_path(o.summary_json, inputs, "--summary-json");
  }
  // From the scene's load to the last write, a signal asks the command to stop gracefully.
  RenderProgress progress;
  progress.stop_cause = "interrupted by a signal";  // the command line's only stop
  const InterruptGuard interrupt(progress.stop_requested);
  constexpr const char* kBeforeRender = "before the render began; nothing was written";
  std::optional<RenderJob> prepared;
  try {
    prepared = prepare_job(request);
  } catch (const Cancelled&) {  // a signal while a large scene was built
    return interrupted_outside_render(kBeforeRender);
  }
  RenderJob& job = *prepared;
  if (const int code = interrupted_outside_render(kBeforeRender)) return code;
  for (const auto& [watching, option] : {std::pair{o.preview_seconds > 0.0, "--preview"},
                                         std::pair{!o.display.empty(), "--display"}}) {
    if (watching && mpi.distributed()) {
      throw InvalidInput(std::string(option) + " is for a render in one process, not under mpirun");
    }
    if (watching && job.share) {
      throw InvalidInput(std::string(option) +
                         " shows a whole render; a part file (--part, --sample-range) is a share "
                         "of one");
    }
  }
  const std::optional<DisplayAddress> display_address =
      o.display.empty() ? std::nullopt : std::optional(parse_display_address(o.display));
  if (mpi.rank() == 0) note_long_request(job);
  // Whether the output holds a file already, before anything of this run writes it: a render
  // stopped short never replaces it (issue 69).
  std::error_code absent;
  const bool output_was_there =
      mpi.rank() == 0 &&
      std::filesystem::exists(std::filesystem::symlink_status(job.output, absent));
  // Rank 0 writes the output (and, alone, keeps a checkpoint).
  const std::unique_ptr<ClaimedOutputs> claimed =
      mpi.rank() == 0 ? std::make_unique<ClaimedOutputs>(job.output, o.summary_json, o.quiet)
                      : nullptr;
  const std::unique_ptr<CheckpointSession> checkpoint = open_checkpoint(o, job, mpi);
  // --display: the image in tev, from its first pass to its end.
  std::unique_ptr<TevDisplay> display;
  if (display_address) {
    display = std::make_unique<TevDisplay>(
        *display_address, std::filesystem::path(job.output).filename().string(),
        film_width(job.settings), film_height(job.settings), frame_placement(job.settings),
        pass_channel_names(job.settings.passes));
  }
  // --preview: the output replaced at the checkpoints' safe points between passes (and
  // --display shown there, every second unless --preview says otherwise).
  RenderPreview preview(job, o.preview_seconds > 0.0, display.get());
  std::optional<Checkpointing> watched;
  if (o.preview_seconds > 0.0 || display) {
    watched = preview.watching(checkpoint ? checkpoint->checkpointing() : nullptr,
                               o.preview_seconds > 0.0 ? o.preview_seconds : 1.0);
  }
  const Checkpointing* checkpointing = watched      ? &*watched
                                       : checkpoint ? checkpoint->checkpointing()
                                                    : nullptr;
  // The image library loads on a second thread while the render runs (rank 0 writes), unless
  // rtiow encodes the format itself (PNG): then it is never loaded.
  if (mpi.rank() == 0) {
    start_parallel_runtime();
    const ImageFormat* format = image_format(job.output);
    if (!format || !format->own_encoder) preload_image_backend();
  }
  RenderResult result;
  try {
    result = render_with_progress(o, job, mpi, progress, checkpointing);
  } catch (const Cancelled&) {  // a signal while the BVH was built: any checkpoint is as it was
    return interrupted_outside_render(kBeforeRender);
  }
  if (mpi.distributed() && !gather_ranks(mpi, job, result)) return 0;
  if (display) display->show(result.film, pass_channels(result, job.settings.passes));
  // A stopped render leaves a file that was there before it (and that no preview of its own
  // replaced) as it was: its samples are in the checkpoint, or else in a file beside it.
  const std::string asked_output = job.output;
  const bool keep_what_was_there = result.stopped && output_was_there && !preview.wrote_output();
  const bool kept_in_checkpoint =
      keep_what_was_there && checkpoint && checkpoint->holds_the_render();
  std::optional<OutputClaim> partial;
  if (keep_what_was_there && !kept_in_checkpoint) {
    job.output = partial_output_path(asked_output);
    check_output_path(job.output, {asked_output});
    partial.emplace(job.output);
  }
  if (!kept_in_checkpoint) {
    const FinalWrite final_write;  // a second signal waits for the image and its checkpoint
    write_or_keep(o, request, job, result, checkpoint.get());
  }
  // The viewer gets its last picture after the files, and no longer than it is allowed.
  if (display) display->finish(progress.stop_requested);
  if (checkpoint) checkpoint->warn_where_kept();  // even when quiet
  int code = 0;
  if (result.stopped) {
    code =
        report_interrupted(job, result, checkpoint.get(),
                           keep_what_was_there ? asked_output : std::string(), kept_in_checkpoint);
  } else {
    if (!o.quiet) print_summary(job, result, mpi);
    code = interrupted_outside_render("after the render ended; the image is complete");
  }
  if (!o.summary_json.empty()) {
    write_text_atomically(o.summary_json,
                          render_summary_json(job, result, mpi.size(), code, !kept_in_checkpoint));
  }
  return code;
}

}  // namespace

std::function<int()> add_render_command(CLI::App& app, const MpiSession& mpi) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Render a scene file or a built-in scene to an image (with no options: the book's cover "
      "at its final settings, to cover.png)");
  const RenderOptionHandles given = add_render_options(cmd, *options);
  return [options, cmd, given, &mpi] {
    if (!cmd->parsed()) return -1;
    JobRequest request = job_request_of(*options, given.scene->count() > 0,
                                        given.output->count() > 0, mpi.rank(), mpi.size());
    if (!options->like.empty()) {
      auto like = std::make_shared<RecordedRequest>(
          read_recorded_request(options->like, "--like image " + quote_value(options->like)));
      const std::set<RequestPart> typed = parts_given(*cmd);
      request = overlay_recorded(*like, std::move(request), typed, output_holds_channels(*cmd),
                                 options->reproducible);
      if (!typed.count(RequestPart::Scene) && !typed.count(RequestPart::SceneSeed)) {
        request.check_loaded_scene = [like](const Scene& scene) {
          check_scene_of_image(*like, scene);
        };
      }
    }
    return run_render(*options, request, mpi);
  };
}

}  // namespace rtiow
