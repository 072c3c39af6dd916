#include "app/checkpoint_session.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>

#include "core/io/error.h"

namespace rtiow {

CheckpointSession::CheckpointSession(const std::string& output, const Scene& scene,
                                     const RenderSettings& settings, double interval_seconds,
                                     bool resume, bool quiet)
    : path_(checkpoint_path(output)),
      identity_(checkpoint_identity(scene, settings)),
      enabled_(interval_seconds > 0.0) {
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
    failure_.clear();
  } catch (const std::exception& e) {
    last_save_ok_ = false;
    failure_ = e.what();
    if (!ended && !warned_) {
      std::fprintf(stderr, "rtiow: warning: %s; the render goes on\n", one_line(e.what()).c_str());
      warned_ = true;
    }
  }
}

}  // namespace rtiow
