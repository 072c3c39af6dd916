#include "app/checkpoint_session.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>

#include "core/limits/error.h"

namespace rtiow {

CheckpointSession::CheckpointSession(const std::string& output, const Scene& scene,
                                     const RenderSettings& settings, double interval_seconds,
                                     bool resume, bool quiet)
    : path_(checkpoint_path(output)), enabled_(interval_seconds > 0.0) {
  // The identity digests the scene's whole text (seconds for a million spheres): only a
  // render that writes or reads a checkpoint needs it.
  if (enabled_ || resume) identity_ = checkpoint_identity(scene, settings);
  if (resume) {
    resumed_ = read_checkpoint(path_, identity_);
    if (!resumed_) {
      if (!quiet) {
        std::fprintf(stderr, "rtiow: no checkpoint %s to resume: rendering from the start\n",
                     quote_value(path_).c_str());
      }
    } else {
      const auto& samples = resumed_->pixels.samples;
      resumed_from_ = samples.empty() ? 0 : *std::max_element(samples.begin(), samples.end());
    }
  }
  checkpointing_.resume = resumed_ ? &*resumed_ : nullptr;
  checkpointing_.interval_seconds = interval_seconds;
  if (enabled_) {
    checkpointing_.save = [this](const RenderState& state, bool ended) { save(state, ended); };
  }
}

void CheckpointSession::save(const RenderState& state, bool ended) {
  try {
    write_checkpoint(path_, identity_, state);
    last_save_ok_ = true;
    kept_at_ = path_;
    failure_.clear();
    return;
  } catch (const std::exception& e) {
    last_save_ok_ = false;
    failure_ = e.what();
    if (!ended && !warned_) {
      std::fprintf(stderr, "rtiow: warning: %s; the render goes on\n", one_line(e.what()).c_str());
      warned_ = true;
    }
  }
  if (!ended) return;
  // The render is over and its place cannot take it (the directory removed or made
  // read-only, the disk full): keep it where temporary files go rather than lose it.
  const char* tmpdir = std::getenv("TMPDIR");
  const std::filesystem::path fallback =
      std::filesystem::path(tmpdir && *tmpdir ? tmpdir : "/tmp") /
      ("rtiow-" + std::to_string(::getpid()) + "-" +
       std::filesystem::path(path_).filename().string());
  try {
    write_checkpoint(fallback.string(), identity_, state);
    last_save_ok_ = true;
    kept_at_ = fallback.string();
  } catch (const std::exception&) {
    // failure_ says why the checkpoint's own place failed, which is what the user can mend.
  }
}

std::string CheckpointSession::how_to_continue() const {
  if (kept_at_ == path_) return "run the same command with --resume";
  return "move it to " + quote_value(path_, kWholePath) + " and run the same command with --resume";
}

}  // namespace rtiow
