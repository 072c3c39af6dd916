#include "core/parallel/cancellation.h"

namespace rtiow {
namespace {

std::atomic<const std::atomic<bool>*> g_flag{nullptr};
std::atomic<const std::atomic<bool>*> g_final_write_flag{nullptr};

}  // namespace

void set_cancellation_flag(const std::atomic<bool>* flag) {
  g_flag.store(flag);
}

bool cancellation_requested() {
  const std::atomic<bool>* flag = g_flag.load(std::memory_order_relaxed);
  return flag && flag->load(std::memory_order_relaxed);
}

void set_final_write_stop_flag(const std::atomic<bool>* flag) {
  g_final_write_flag.store(flag);
}

bool final_write_stop_requested() {
  const std::atomic<bool>* flag = g_final_write_flag.load(std::memory_order_relaxed);
  return flag && flag->load(std::memory_order_relaxed);
}

}  // namespace rtiow
