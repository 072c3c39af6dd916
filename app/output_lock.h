#pragma once
// One render at a time per output: two renders to one file would both report success while
// one silently replaced the other (and they would share a checkpoint). A render holds an
// advisory lock (flock) on a hidden file beside its output, `.<name>.rtiow-lock`, which
// holds its pid and is removed when it ends; a lock left by a killed render is free again
// (the kernel releases it with the process), so a stale file never blocks anyone.

#include <string>

namespace rtiow {

class OutputLock {
 public:
  // Throws InvalidInput naming the output and the other render's pid when it is held.
  // Where no lock file can be made, renders unlocked (the output's own checks decide).
  explicit OutputLock(const std::string& output);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace rtiow
