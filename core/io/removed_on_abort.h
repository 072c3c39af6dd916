#pragma once
// Files (and helper processes) this process must not leave behind even when it ends at once (a
// second Ctrl-C, a fatal signal handled by rtiow): a temporary being written, a lock file. Each is
// registered by its directory's descriptor and its name while it exists; remove_files_now() unlinks
// them all and is async-signal-safe, so a signal handler may call it just before _exit.

#include <string>

namespace rtiow {

// Registers (dir_fd, name) for as long as it lives. Names longer than a file name may be
// are not registered (the file is then removed only by its owner's normal path). A directory
// (one a command made for its outputs) is removed after the files, and only if it is empty.
class RemovedOnAbort {
 public:
  enum Kind { File, EmptyDirectory };
  RemovedOnAbort(int dir_fd, const std::string& name, Kind kind = File);
  ~RemovedOnAbort();
  RemovedOnAbort(const RemovedOnAbort&) = delete;
  RemovedOnAbort& operator=(const RemovedOnAbort&) = delete;

 private:
  int slot_ = -1;
};

// A helper process rtiow started and waits for (core/io/child_process.h): ended with SIGTERM if
// rtiow must end at once, so no helper outlives it writing into a temporary.
class EndedOnAbort {
 public:
  explicit EndedOnAbort(int pid);
  ~EndedOnAbort();
  EndedOnAbort(const EndedOnAbort&) = delete;
  EndedOnAbort& operator=(const EndedOnAbort&) = delete;

 private:
  int slot_ = -1;
};

// Ends every registered helper and unlinks every registered file. Async-signal-safe: only
// atomics, kill and unlinkat.
void remove_files_now() noexcept;

}  // namespace rtiow
