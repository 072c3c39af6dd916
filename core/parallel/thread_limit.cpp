#include "core/parallel/thread_limit.h"

#include <mutex>
#include <stdexcept>
#include <string>

#include "core/limits/error.h"
#include "core/limits/setting_name.h"
#include "core/parallel/thread_probe.h"

namespace rtiow {
namespace {

std::mutex g_mutex;
int g_verified = 1;  // this thread

}  // namespace

void require_threads(int threads) {
  const std::lock_guard<std::mutex> guard(g_mutex);
  if (threads <= g_verified) return;
  int error = 0;
  const int started = threads_that_can_start_together(threads - 1, &error);
  if (error != 0) {
    throw std::runtime_error("cannot start " + std::to_string(threads) + " threads (" +
                             std::to_string(started + 1) +
                             " could run): " + system_error_text(error) + "; " +
                             setting("threads", std::to_string(started + 1)) + " asks for fewer");
  }
  g_verified = threads;
}

bool a_thread_can_start() {
  return threads_that_can_start_together(1) == 1;
}

}  // namespace rtiow
