#pragma once
// What a measurement says when its own times cannot be right: on a machine busy with other work,
// or in a run too short to time (--quick), the figures are not the machine's, and a reader who
// sees "thread scaling 0.84x" or a negative time saved is told so rather than left to believe it.

#include <string>
#include <vector>

namespace rtiow {

// More threads cannot trace slower than one on an idle machine. "" when the rates are
// plausible, else the warning (no trailing newline).
std::string thread_scaling_warning(int threads, double one_thread_rate, double threads_rate);

// Fewer bounces cannot take longer than the deepest limit: seconds per depth limit, as
// measured. "" when none of the shallower limits took longer than the deepest one.
std::string depth_timing_warning(const std::vector<double>& depths,
                                 const std::vector<double>& seconds);

}  // namespace rtiow
