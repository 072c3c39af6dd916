#pragma once
// One door for every file rtiow writes, in every command (render, parts, merge, diff's
// pictures, scene, bench, accuracy) and in a program that calls the library.
//
// A command claims each of its outputs before its work: the claim opens the output's
// directory once and holds it for every write of the command (so a directory renamed or
// swapped for a link meanwhile changes nothing), takes the output's lock, and removes the
// temporaries a killed rtiow left for that name. Two commands of any kinds aimed at one
// output: the second is refused in one line, before any work. Every write
// (core/io/atomic_file.h) goes through the claim of its target; a write to a name no live
// claim holds claims it for the time of the write, so nothing bypasses the lock.
//
// The lock is an advisory lock (flock) on a hidden file beside the output,
// `.<name>.rtiow-lock`, holding its pid and removed when the claim ends; one left by a killed
// rtiow is free again (the kernel releases it with the process). Its name lies in a directory
// others may write, so it is input like any other: created exclusively, and a file already
// there is used only if it is a regular file of this user with one link; anything else (a
// link, a directory, a FIFO, another user's file) is refused with why. The lock never fails
// open: a command that cannot take it does not start. A cleaner of temporary files may remove
// the lock file while its holder runs, so the claim holds a second lock that no file carries:
// an abstract socket (Linux) named after the output's directory and name, freed with the
// process; a command whose lock file was taken away still keeps out a second one.

#include <memory>
#include <string>

#include "core/io/removed_on_abort.h"

namespace rtiow {

class OutputClaim {
 public:
  // Throws InvalidInput naming the output and why it cannot be claimed (the other rtiow's pid
  // when the lock is held).
  explicit OutputClaim(const std::string& path);
  ~OutputClaim();
  OutputClaim(const OutputClaim&) = delete;
  OutputClaim& operator=(const OutputClaim&) = delete;

  const std::string& path() const { return path_; }
  // The output's directory, held open, and the output's name in it.
  int directory() const { return dir_fd_; }
  const std::string& name() const { return name_; }
  // How many stale temporaries of this output the claim removed.
  int removed_temporaries() const { return removed_; }

  // The live claim of the output `path` names (compared as a directory and a name, however
  // spelt), or nullptr.
  static const OutputClaim* find(const std::string& path);

 private:
  void open_directory();  // the output's directory, held; refuses an output named twice
  // Locks the lock file `fd` (created by this claim or found), binds the name's socket and
  // records the claim; false where its holder removed it meanwhile (then try again).
  bool hold_lock(int fd, bool created);
  [[noreturn]] void refuse_lock(const std::string& why);  // closes what is open, throws

  std::string path_, name_, lock_name_;
  int dir_fd_ = -1;
  int lock_fd_ = -1;
  int name_lock_fd_ = -1;  // the lock a cleaner cannot remove (output_claim.cpp)
  int removed_ = 0;
  std::unique_ptr<RemovedOnAbort> removed_on_abort_;
};

}  // namespace rtiow
