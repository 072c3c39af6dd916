#include "core/io/removed_on_abort.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstring>

namespace rtiow {
namespace {

// A fixed table: a signal handler can neither allocate nor lock. A command holds a lock per
// output it claimed (accuracy: four with its cached reference) and a temporary or two at once.
constexpr int kFree = -1, kFilling = -2;
struct Slot {
  std::atomic<int> dir_fd{kFree};  // kFree, kFilling, or the directory of `name`
  char name[256] = {};
  int flags = 0;  // unlinkat's: AT_REMOVEDIR for a directory
};
std::array<Slot, 16> g_slots;
std::array<std::atomic<int>, 4> g_children{0, 0, 0, 0};  // pids, 0 when free
static_assert(std::atomic<int>::is_always_lock_free, "read from a signal handler");

}  // namespace

RemovedOnAbort::RemovedOnAbort(int dir_fd, const std::string& name, Kind kind) {
  if (dir_fd < 0 || name.empty() || name.size() >= sizeof(Slot::name)) return;
  for (int i = 0; i < int(g_slots.size()); ++i) {
    int expected = kFree;
    if (!g_slots[std::size_t(i)].dir_fd.compare_exchange_strong(expected, kFilling)) continue;
    Slot& slot = g_slots[std::size_t(i)];
    std::memcpy(slot.name, name.c_str(), name.size() + 1);
    slot.flags = kind == EmptyDirectory ? AT_REMOVEDIR : 0;
    slot.dir_fd.store(dir_fd);  // the name is whole before a handler can see the slot
    slot_ = i;
    return;
  }
}

RemovedOnAbort::~RemovedOnAbort() {
  if (slot_ >= 0) g_slots[std::size_t(slot_)].dir_fd.store(kFree);
}

EndedOnAbort::EndedOnAbort(int pid) {
  for (int i = 0; i < int(g_children.size()) && pid > 0; ++i) {
    int expected = 0;
    if (g_children[std::size_t(i)].compare_exchange_strong(expected, pid)) {
      slot_ = i;
      return;
    }
  }
}

EndedOnAbort::~EndedOnAbort() {
  if (slot_ >= 0) g_children[std::size_t(slot_)].store(0);
}

void remove_files_now() noexcept {
  for (std::atomic<int>& child : g_children) {
    if (const int pid = child.load(); pid > 0) ::kill(pid, SIGTERM);
  }
  // Files first, then directories, outermost last (a few passes: a directory goes once
  // empty, whatever order the slots hold them in).
  for (const int pass : {0, AT_REMOVEDIR, AT_REMOVEDIR, AT_REMOVEDIR, AT_REMOVEDIR}) {
    for (Slot& slot : g_slots) {
      const int dir_fd = slot.dir_fd.load();
      if (dir_fd >= 0 && slot.flags == pass) ::unlinkat(dir_fd, slot.name, pass);
    }
  }
}

}  // namespace rtiow
