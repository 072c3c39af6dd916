#pragma once
// A render's state on disk (core/render/render_state.h), so a render that a signal, an OOM
// kill or a power cut ended can be continued, and a finished one refined, to the bits an
// uninterrupted render gives.
//
// The file: a text header ("rtiow-checkpoint 2", then "key value" lines naming the request
// it belongs to and the state's scalars, then "end"), the per-pixel state in fixed-size
// little-endian records, and a 64-bit checksum of all that precedes it. It is written to a
// temporary beside the target, flushed to the disk (fsync) and renamed over the target, so
// a kill at any moment leaves the old checkpoint or the new one, never a torn one.

#include <optional>
#include <string>

#include "core/render/render.h"
#include "core/render/render_state.h"
#include "core/scene/scene.h"

namespace rtiow {

// The request a checkpoint belongs to: what must match for a render to continue it.
struct CheckpointIdentity {
  std::string version;  // rtiow's: the sample streams may change between versions
  std::string scene;    // a digest of the scene
  std::string size;     // "WxH"
  std::string depth, seed, sampler;
  std::string first_sample;  // of a share of a render
  std::string mode;          // uniform, or the adaptive mode with its parameters and --spp
};

CheckpointIdentity checkpoint_identity(const Scene& scene, const RenderSettings& settings);

// What differs between the request a checkpoint was made for and this one, in words
// ("seed: the checkpoint's 1, this render's 2"); empty when this one may continue it.
std::string identity_mismatch(const CheckpointIdentity& checkpoint, const CheckpointIdentity& now);

// Where a render to `output` keeps its checkpoint: beside it, named after it.
std::string checkpoint_path(const std::string& output);

// Writes atomically and durably; throws std::runtime_error naming the path and the
// system's reason.
void write_checkpoint(const std::string& path, const CheckpointIdentity& identity,
                      const RenderState& state);

// The state in the checkpoint at `path`, or nothing if there is no file. Throws
// InvalidInput naming the file when it is not a whole checkpoint, and naming what differs
// when it belongs to another request.
std::optional<RenderState> read_checkpoint(const std::string& path,
                                           const CheckpointIdentity& expected);

}  // namespace rtiow
