#pragma once
// Wall-clock time for the render loop's decisions (pass sizes, time limits). Timing decides
// how samples are grouped and when a time-limited render stops, never what a sample is.

#include <chrono>

namespace rtiow {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace rtiow
