#pragma once
// A render's state on disk (core/render/render_state.h), so a render that a signal, an OOM
// kill or a power cut ended can be continued, and a finished one refined, to the bits an
// uninterrupted render gives.
//
// The file: a text header ("rtiow-checkpoint 4", then "key value" lines naming the render
// it belongs to (core/render/render_identity.h) and the state's scalars, then "end"), the per-pixel
// state, and a 64-bit checksum of all that precedes it. Each pixel is a record of variable-length
// integers (LEB128): its count (as the difference from the previous pixel's), its rays, its
// adaptive target (as the difference from its count), its nine exact sums, whose high bytes are
// mostly zero, and with passes asked the seven sums they are the mean of (zigzagged, being
// signed): 57 bytes a pixel for the cover at 500 spp where version 2's fixed records took
// 156 (formats 2 and 3 are still read). It is written through core/io/atomic_file.h (an exclusive
// temporary, flushed, renamed), so a kill at any moment leaves the old checkpoint or the new
// one, never a torn one, and never writes through a link.
//
// A checkpoint is input like a scene file, and its format and checksum are public: every
// field is checked against the request and rtiow's limits before it is used (sizes before
// anything is allocated; counts and targets within the render's cap, each pixel's sums and
// rays within what its samples can hold, times finite and non-negative), and the file is
// opened without following a link or blocking.

#include <cstdint>
#include <optional>
#include <string>

#include "core/render/render_identity.h"
#include "core/render/render_settings.h"
#include "core/render/render_state.h"
#include "core/scene/scene.h"

namespace rtiow {

// Where a render to `output` keeps its checkpoint: beside it, named after it.
std::string checkpoint_path(const std::string& output);

// Writes atomically and durably; throws std::runtime_error naming the path and the
// system's reason.
void write_checkpoint(const std::string& path, const RenderIdentity& identity,
                      const RenderState& state);

// The state in the checkpoint at `path`, or nothing if there is no file. Throws
// InvalidInput naming the file when it is not a whole, valid checkpoint of `settings`, and
// naming what differs when it belongs to another request.
std::optional<RenderState> read_checkpoint(const std::string& path, const RenderIdentity& expected,
                                           const RenderSettings& settings);

// What a checkpoint's header says, read without its pixels: whose it is and how far it got.
struct CheckpointSummary {
  RenderIdentity identity;
  // Over its pixels (a version 2 checkpoint does not say).
  std::optional<std::uint64_t> least_samples, most_samples;
};

// The summary of the checkpoint at `path`, or nothing if there is no file. Throws
// InvalidInput naming the file when its header is not a checkpoint's.
std::optional<CheckpointSummary> read_checkpoint_summary(const std::string& path);

}  // namespace rtiow
