#pragma once
// One render at a time per output: two renders to one file would both report success while
// one silently replaced the other (and they would share a checkpoint). A render holds an
// advisory lock (flock) on a hidden file beside its output, `.<name>.rtiow-lock`, which holds
// its pid and is removed when it ends; a lock left by a killed render is free again (the
// kernel releases it with the process), so a stale file never blocks anyone.
//
// The lock's name is in a directory others may write, so it is input like any other: it is
// created exclusively (never through a link, never a file someone else made), and a file
// already there is used only if it is a regular file of this user with one link; anything
// else (a link, a directory, a FIFO, another user's file) is refused with why. The lock never
// fails open: a render that cannot take it does not start.

#include <memory>
#include <string>

#include "core/io/removed_on_abort.h"

namespace rtiow {

class OutputLock {
 public:
  // Throws InvalidInput naming the output and why the lock cannot be taken (the other
  // render's pid when it is held).
  explicit OutputLock(const std::string& output);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  std::string name_;
  int dir_fd_ = -1;
  int fd_ = -1;
  std::unique_ptr<RemovedOnAbort> removed_on_abort_;
};

}  // namespace rtiow
