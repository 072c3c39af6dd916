#include "core/session/checkpoint_session.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>

#include "core/io/atomic_file.h"
#include "core/io/output_claim.h"
#include "core/limits/error.h"
#include "core/limits/setting_name.h"

namespace rtiow {
namespace {

// "253 spp done", "16-4096 spp done", or nothing for an old file that does not tell.
std::string samples_done(const CheckpointSummary& summary) {
  if (!summary.least_samples || !summary.most_samples) return "";
  const std::string least = std::to_string(*summary.least_samples);
  const std::string most = std::to_string(*summary.most_samples);
  return (least == most ? most : least + "-" + most) + " spp done";
}

// Removes `path` if it is a file or a link (never a directory's contents), through the
// directory its claim holds open where it has one: a directory renamed or swapped for a link
// since the claim then loses nothing of another place's (issue 69).
void remove_file(const std::string& path) {
  struct stat info {};
  if (const OutputClaim* claim = OutputClaim::find(path)) {
    const int dir = claim->directory();
    const char* name = claim->name().c_str();
    if (::fstatat(dir, name, &info, AT_SYMLINK_NOFOLLOW) == 0 && !S_ISDIR(info.st_mode)) {
      ::unlinkat(dir, name, 0);
    }
    return;
  }
  if (::lstat(path.c_str(), &info) == 0 && !S_ISDIR(info.st_mode)) ::unlink(path.c_str());
}

}  // namespace

CheckpointSession::CheckpointSession(const std::string& output, const Scene& scene,
                                     const RenderSettings& settings,
                                     const CheckpointOptions& options)
    : path_(checkpoint_path(output)), options_(options) {
  // The identity digests the scene (about a second for a million spheres): only a render
  // that writes or reads a checkpoint needs it.
  if (options_.interval_seconds > 0.0 || options_.resume) {
    identity_ = render_identity(scene, settings);
  }
  if (options_.resume) {
    resumed_ = read_checkpoint(path_, identity_, settings);
    if (!resumed_) {
      if (!options_.quiet) {
        std::fprintf(stderr, "rtiow: no checkpoint %s to resume: rendering from the start\n",
                     quote_value(path_).c_str());
      }
    } else {
      const auto& samples = resumed_->pixels.samples;
      resumed_from_ = samples.empty() ? 0 : *std::max_element(samples.begin(), samples.end());
      wrote_beside_ = true;  // this render's now: replaced as it goes, removed when it is done
    }
  } else if (options_.restart) {
    remove_file(path_);
  } else if (options_.interval_seconds > 0.0) {
    refuse_unless_told();
  }
  checkpointing_.resume = resumed_ ? &*resumed_ : nullptr;
  checkpointing_.interval_seconds = options_.interval_seconds;
  if (uses_state()) {  // the identity is known: either computed it above
    checkpointing_.save = [this](const RenderState& state, SaveReason reason) {
      save(state, reason);
    };
  }
}

// A render that would replace a checkpoint is refused, naming it, unless told which way.
void CheckpointSession::refuse_unless_told() {
  std::optional<CheckpointSummary> there;
  try {
    there = read_checkpoint_summary(path_);
  } catch (const InvalidInput& e) {
    throw InvalidInput(std::string(e.what()) + "; " + setting("restart") + " replaces it");
  }
  if (!there) return;
  const std::string differs = identity_mismatch(there->identity, identity_, "the checkpoint's");
  const std::string done = samples_done(*there);
  if (differs.empty()) {
    throw InvalidInput("checkpoint " + quote_value(path_) +
                       " holds an unfinished render of this "
                       "request" +
                       (done.empty() ? "" : " (" + done + ")") + ": add " + setting("resume") +
                       " to continue it, or " + setting("restart") +
                       " to discard it and render from the start");
  }
  throw InvalidInput("checkpoint " + quote_value(path_) + " holds another render (" +
                     (done.empty() ? "" : done + "; ") + differs + "): add " + setting("restart") +
                     " to discard it, or choose another " + setting("output"));
}

bool CheckpointSession::save_to(const std::string& path, const RenderState& state) {
  try {
    write_checkpoint(path, identity_, state);
    return true;
  } catch (const std::exception& e) {
    failure_ = e.what();
    return false;
  }
}

void CheckpointSession::save(const RenderState& state, SaveReason reason) {
  if (reason == SaveReason::Finished) {
    finished_ = true;
    if (!options_.keep_state) return;  // written only if the image cannot be (image_lost)
  }
  if (save_to(path_, state)) {
    wrote_beside_ = true;
    failure_.clear();
    if (reason != SaveReason::Periodic) kept_at_ = path_;
    return;
  }
  if (reason == SaveReason::Periodic) {
    if (!warned_) {
      std::fprintf(stderr, "rtiow: warning: %s; the render goes on\n", one_line(failure_).c_str());
      warned_ = true;
    }
    return;
  }
  // The render is over and its place cannot take it (the directory removed or made
  // read-only, the disk full): keep it where temporary files go rather than lose it, under a
  // name no one else can have made first.
  const char* tmpdir = std::getenv("TMPDIR");
  std::string fallback;
  try {
    fallback = (std::filesystem::path(tmpdir && *tmpdir ? tmpdir : "/tmp") /
                ("rtiow-" + unpredictable_letters(8) + "-" +
                 std::filesystem::path(path_).filename().string()))
                   .string();
  } catch (const std::exception&) {
    return;
  }
  const std::string why = failure_;
  if (save_to(fallback, state)) kept_at_ = fallback;
  failure_ = why;  // the checkpoint's own place's failure is what the user can mend
}

void CheckpointSession::image_written() {
  if (!finished_ || options_.keep_state) return;  // stopped: kept to resume; or asked to keep
  if (wrote_beside_) remove_file(path_);
  wrote_beside_ = false;
}

void CheckpointSession::image_lost(const RenderState& state) {
  if (!kept_at_.empty() || !checkpointing_.save) return;
  save(state, SaveReason::Stopped);
}

std::string CheckpointSession::how_to_continue() const {
  const std::string again = "run the same command with " + setting("resume");
  if (kept_at_ == path_) return again;
  return "move it to " + quote_value(path_, kWholePath) + " and " + again;
}

void CheckpointSession::warn_where_kept() const {
  if (failure_.empty()) return;
  const bool wanted = !finished_ || options_.keep_state;  // a stopped render, or --keep-state
  if (!wanted) return;
  if (!kept_at_.empty() && kept_at_ != path_) {
    std::fprintf(stderr, "rtiow: warning: %s; the render's state is kept in %s instead (%s)%s\n",
                 one_line(failure_).c_str(), quote_value(kept_at_, kWholePath).c_str(),
                 how_to_continue().c_str(),
                 wrote_beside_ ? "; the checkpoint beside the output is older and holds less" : "");
    return;
  }
  if (kept_at_.empty()) {
    std::fprintf(stderr, "rtiow: warning: %s; the render's state is not kept\n",
                 one_line(failure_).c_str());
  }
}

}  // namespace rtiow
