#include "core/parallel/thread_limit.h"

#include <pthread.h>

#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/limits/error.h"
#include "core/limits/setting_name.h"

namespace rtiow {
namespace {

std::mutex g_mutex;
int g_verified = 1;  // this thread

void* wait_for_release(void* gate) {
  // Each thread holds until all are started, so they run at once.
  std::lock_guard<std::mutex> hold(*static_cast<std::mutex*>(gate));
  return nullptr;
}

}  // namespace

void require_threads(int threads) {
  const std::lock_guard<std::mutex> guard(g_mutex);
  if (threads <= g_verified) return;
  std::mutex gate;
  std::vector<pthread_t> started;
  int error = 0;
  {
    std::lock_guard<std::mutex> closed(gate);
    for (int i = 1; i < threads; ++i) {
      pthread_attr_t small{};
      pthread_attr_init(&small);
      pthread_attr_setstacksize(&small, 1 << 16);
      pthread_t thread{};
      error = ::pthread_create(&thread, &small, wait_for_release, &gate);
      pthread_attr_destroy(&small);
      if (error != 0) break;
      started.push_back(thread);
    }
  }
  for (const pthread_t thread : started) ::pthread_join(thread, nullptr);
  if (error != 0) {
    throw std::runtime_error(
        "cannot start " + std::to_string(threads) + " threads (" +
        std::to_string(started.size() + 1) + " could run): " + system_error_text(error) + "; " +
        setting("threads", std::to_string(started.size() + 1)) + " asks for fewer");
  }
  g_verified = threads;
}

bool a_thread_can_start() {
  std::mutex gate;
  pthread_t thread{};
  if (::pthread_create(&thread, nullptr, wait_for_release, &gate) != 0) return false;
  ::pthread_join(thread, nullptr);
  return true;
}

}  // namespace rtiow
