#include "core/parallel/cancellation.h"

namespace rtiow {
namespace {

std::atomic<const std::atomic<bool>*> g_flag{nullptr};

}  // namespace

void set_cancellation_flag(const std::atomic<bool>* flag) {
  g_flag.store(flag);
}

bool cancellation_requested() {
  const std::atomic<bool>* flag = g_flag.load(std::memory_order_relaxed);
  return flag && flag->load(std::memory_order_relaxed);
}

}  // namespace rtiow
