#include "core/measure/timing_warnings.h"

#include <cstddef>
#include <cstdio>

#include "core/limits/setting_name.h"

namespace rtiow {

namespace {
std::string why_slower() {
  return "another program was running, or the run was too short to time (" + setting("quick") + ")";
}
}  // namespace

std::string thread_scaling_warning(int threads, double one_thread_rate, double threads_rate) {
  if (threads <= 1 || !(threads_rate < one_thread_rate)) return "";
  char text[256];
  std::snprintf(text, sizeof text,
                "warning: %d threads traced slower than 1 (%.2fx): %s; these rates are not this "
                "machine's",
                threads, threads_rate / one_thread_rate, why_slower().c_str());
  return text;
}

std::string depth_timing_warning(const std::vector<double>& depths,
                                 const std::vector<double>& seconds) {
  std::size_t deepest = 0;
  for (std::size_t i = 1; i < depths.size() && i < seconds.size(); ++i) {
    if (depths[i] > depths[deepest]) deepest = i;
  }
  for (std::size_t i = 0; i < depths.size() && i < seconds.size(); ++i) {
    if (depths[i] < depths[deepest] && seconds[i] > seconds[deepest]) {
      char text[256];
      std::snprintf(text, sizeof text,
                    "warning: depth %.0f took longer than depth %.0f (a negative time saved): "
                    "these times are noise: %s",
                    depths[i], depths[deepest], why_slower().c_str());
      return text;
    }
  }
  return "";
}

}  // namespace rtiow
