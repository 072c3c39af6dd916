#pragma once
// What a render session says in words, for any front end to print: a request that would take
// days, and where a render stopped short went (its image, its checkpoint, the file it left
// alone). Settings are named through setting() (core/limits/setting_name.h).

#include <string>

#include "core/render/render_job.h"
#include "core/session/render_session.h"

namespace rtiow {

// "1000000 spp at 1200x800 is 9.6e+11 samples, about 2.22 days on a 2-core machine; ..." for a
// uniform render without a time limit that asks for more than a day of work on a 2-core machine
// (the cover runs at about 5e6 samples per second there); empty otherwise. The count is
// accepted (a farm or a long night may mean it), but not silently.
std::string long_request_note(const RenderSettings& settings);

// "wrote 37 spp (of 100 asked) to cover.png; the render is kept in ...", or, where the session
// left alone a file that was there before the render, "37 spp (of 100 asked) kept in
// 'cover.png.rtiow-checkpoint' (...); 'cover.png', which this render did not finish, is left as
// it was", or "wrote ... to cover.partial.png; 'cover.png' ...".
std::string stopped_render_report(const RenderJob& job, const RenderResult& result,
                                  const CheckpointSession* checkpoint, const SessionEnd& end);

}  // namespace rtiow
