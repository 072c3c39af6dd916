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
#include "app/render/render_options.h"
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
#include "core/scene/builtin_scenes.h"
#include "core/session/checkpoint_session.h"
#include "core/session/progress_display.h"
#include "core/session/render_preview.h"
#include "core/session/render_session.h"
#include "core/session/render_summary.h"
#include "core/session/session_report.h"
#include "core/session/tev_display.h"
#include "core/session/work_display.h"

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
                                  RenderSession& session) {
  std::unique_ptr<ProgressDisplay> display;
  if (!o.quiet && mpi.rank() == 0) {
    display = std::make_unique<ProgressDisplay>(progress, job.settings);
  }
  return session.render(progress);
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
  result.replicate_ratios = job.settings.estimate_error ? estimate.replicate_ratios : nullptr;
  restore_whole_job(job.samples_asked, job.settings);
  return true;
}

// "rendered cover 1200x800, 500 spp, depth 50, embree, 2 threads: ... -> path"
void print_summary(const RenderJob& job, const RenderResult& result, const MpiSession& mpi,
                   const std::optional<DenoiseFigures>& denoised) {
  const RenderSettings& s = job.settings;
  const double rays = double(result.rays_traced);
  const int threads = thread_count(s.threads);  // the threads used (core/parallel/thread_count.h)
  const std::string ranks = mpi.distributed() ? std::to_string(mpi.size()) + " ranks x " : "";
  const RenderOutcome outcome = describe_outcome(s, result);
  char judging[48] = "";
  if (result.judging_seconds > 0)
    std::snprintf(judging, sizeof judging, " (%.2f s of it denoising)", result.judging_seconds);
  std::fprintf(stderr,
               "rendered %s %dx%d%s, %s%s, depth %d, %s, %s%d thread%s: %.2f s%s, %.3g rays, "
               "%.2f Mrays/s -> %s\n",
               job.scene.name.c_str(), s.width, s.height,
               s.crop ? (" crop " + to_string(*s.crop)).c_str() : "", outcome.samples.c_str(),
               outcome.error.empty() ? "" : (", " + outcome.error).c_str(), s.max_depth,
               to_string(s.accel).c_str(), ranks.c_str(), threads, threads == 1 ? "" : "s",
               result.render_seconds, judging, rays, tracing_mrays_per_second(result),
               one_line(job.output).c_str());
  if (denoised) {
    std::fprintf(stderr, "%s\n", describe(*denoised).c_str());
  }
}

// What the session around the render keeps and shows: no checkpoint under mpirun (each rank
// holds only its share), where --resume is refused; rank 0 alone writes.
SessionOptions session_options(const RenderOptions& o, const MpiSession& mpi) {
  if (mpi.distributed() && o.resume) {
    throw InvalidInput("--resume is for a render in one process, not under mpirun");
  }
  SessionOptions options;
  options.writes_output = mpi.rank() == 0;
  options.checkpointed = !mpi.distributed();
  options.checkpoint.interval_seconds = o.checkpoint_seconds;
  options.checkpoint.resume = o.resume, options.checkpoint.restart = o.restart;
  options.checkpoint.keep_state = o.keep_state, options.checkpoint.quiet = o.quiet;
  options.preview_seconds = o.preview_seconds;
  if (!o.display.empty()) options.display = parse_display_address(o.display);
  options.reproducible = o.reproducible;
  check_session_options(options);
  return options;
}

// A signal that arrived where the render could not stop for it (the scene's load, the final
// writes) ends the command once they are done, in rtiow's words; 0 if none did.
int interrupted_outside_render(const char* when) {
  const int signal = InterruptGuard::signal_received();
  if (signal == 0) return 0;
  std::fprintf(stderr, "rtiow: interrupted (signal %d) %s\n", signal, when);
  return 128 + signal;
}

// --preview and --display watch a whole render in one process.
void refuse_watching_ranks(const RenderOptions& o, const MpiSession& mpi) {
  for (const auto& [watching, option] : {std::pair{o.preview_seconds > 0.0, "--preview"},
                                         std::pair{!o.display.empty(), "--display"}}) {
    if (watching && mpi.distributed()) {
      throw InvalidInput(std::string(option) + " is for a render in one process, not under mpirun");
    }
  }
}

// What the session's claims and checkpoint found at the start, said unless quiet.
void report_start(const RenderSession& session, const std::string& output, bool quiet) {
  if (quiet) return;
  if (const int removed = session.removed_temporaries(); removed > 0) {
    std::fprintf(stderr, "rtiow: removed %d temporar%s an interrupted rtiow left beside %s\n",
                 removed, removed == 1 ? "y" : "ies", quote_value(output).c_str());
  }
  const CheckpointSession* checkpoint = session.checkpoint();
  if (checkpoint && checkpoint->resumed_from()) {
    std::fprintf(stderr, "rtiow: resuming from %s (%u spp done)\n",
                 quote_value(checkpoint->path()).c_str(), *checkpoint->resumed_from());
  }
}

// The render's end: the final write (a second signal waits for it), the viewer's last picture,
// the lines and the summary.
int end_render(const RenderOptions& o, const RenderJob& job, RenderResult& result,
               RenderSession& session, const RenderProgress& progress, const MpiSession& mpi) {
  SessionEnd end;
  {
    // A second signal waits for the image and its checkpoint (not for the denoiser).
    const FinalWrite final_write(o.denoise && !job.share);
    WorkProgress denoising;
    std::optional<WorkDisplay> display;
    if (o.denoise && !job.share && !o.quiet)
      display.emplace(std::vector<WorkPhase>{{&denoising, "denoised"}}, &progress.stop_requested);
    end = session.deliver(result, &denoising);
  }
  session.let_viewer_finish(progress.stop_requested);
  if (session.checkpoint()) session.checkpoint()->warn_where_kept();  // even when quiet
  int code = 0;
  if (result.stopped) {
    std::fprintf(stderr, "rtiow: interrupted: %s\n",
                 stopped_render_report(job, result, session.checkpoint(), end).c_str());
    code = 128 + InterruptGuard::signal_received();
  } else {
    if (!o.quiet) print_summary(job, result, mpi, end.denoised);
    if (o.denoise && !end.denoised && !end.written.empty() && !job.share) {
      std::fprintf(stderr, "rtiow: warning: the image is not denoised: %s\n",
                   why_not_denoised(result).c_str());
    }
    code = interrupted_outside_render("after the render ended; the image is complete");
  }
  if (!o.summary_json.empty()) {
    write_text_atomically(
        o.summary_json,
        render_summary_json(job, result, mpi.size(), code, !end.kept_in_checkpoint, end.denoised));
  }
  return code;
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
  refuse_watching_ranks(o, mpi);
  const SessionOptions options = session_options(o, mpi);
  if (const std::string note = long_request_note(job.settings); !note.empty() && mpi.rank() == 0) {
    std::fprintf(stderr, "rtiow: note: %s\n", note.c_str());
  }
  RenderSession session(job, request, options);  // rank 0 claims the output and its checkpoint
  std::optional<OutputClaim> summary_claim;
  if (mpi.rank() == 0 && !o.summary_json.empty()) summary_claim.emplace(o.summary_json);
  report_start(session, job.output, o.quiet);
  RenderResult result;
  try {
    result = render_with_progress(o, job, mpi, progress, session);
  } catch (const Cancelled&) {  // a signal while the BVH was built: any checkpoint is as it was
    return interrupted_outside_render(kBeforeRender);
  }
  if (mpi.distributed() && !gather_ranks(mpi, job, result)) return 0;
  return end_render(o, job, result, session, progress, mpi);
}

}  // namespace

int run_render_command(const RenderCommand& command, const MpiSession& mpi) {
  RenderOptions o = command.options;  // --like may give it the image's --reproducible
  JobRequest request =
      job_request_of(o, command.scene_named, command.output_given, mpi.rank(), mpi.size());
  if (!o.like.empty()) {
    auto like = std::make_shared<RecordedRequest>(
        read_recorded_request(o.like, "--like image " + quote_value(o.like)));
    request = overlay_recorded(*like, std::move(request), command.typed,
                               command.output_holds_channels, o.reproducible);
    if (!command.typed.count(RequestPart::Scene) && !command.typed.count(RequestPart::SceneSeed)) {
      request.check_loaded_scene = [like](const Scene& scene) {
        check_scene_of_image(*like, scene);
      };
    }
  }
  return run_render(o, request, mpi);
}

}  // namespace rtiow
