#pragma once
// Writing a file so that it is never seen half-written and no one else's file is touched.
// Every write goes through the claim of its target (core/io/output_claim.h: the lock, and the
// directory opened once and held). The content goes to a temporary that rtiow creates itself,
// exclusively (O_CREAT|O_EXCL|O_NOFOLLOW: never through a link, never a file someone made
// first), under an unpredictable name, in that held directory (so the rename stays in that
// directory and on one file system, and is atomic). It is flushed to the disk and renamed over the
// target only when complete; a link at the target's name is replaced, never followed. On failure,
// or when the process must end at once (core/io/removed_on_abort.h), the temporary is removed and
// the target left as it was.
//
// A temporary is named ".<target's name>.rtiow-tmp-<8 random letters and digits>", so one
// that a kill -9 left behind is recognised as rtiow's (remove_stale_temporaries).

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace rtiow {

// Calls `write(fd)` with the temporary open for writing (and reading back); it returns false (and
// sets `reason`) or throws on failure. Throws std::runtime_error "cannot write 'path': reason".
void write_atomically(const std::string& path,
                      const std::function<bool(int fd, std::string& reason)>& write);

// The same for bytes and for text.
void write_bytes_atomically(const std::string& path, const std::vector<unsigned char>& bytes);
void write_text_atomically(const std::string& path, const std::string& text);

// `count` letters and digits from the system's random source: a name no one can guess.
std::string unpredictable_letters(std::size_t count);

// Whether `name` (a file name, no directory) is one of rtiow's temporaries for a target
// whose file name is `target_name`.
bool is_temporary_of(const std::string& target_name, const std::string& name);

// Removes the temporaries of the target `target_name` in the directory `dir_fd` that a killed
// rtiow left: only names of rtiow's pattern, only regular files (not links) owned by this
// user. The caller holds the target's lock (core/io/output_claim.h), so no live rtiow is
// writing them. Returns how many.
int remove_stale_temporaries(int dir_fd, const std::string& target_name);

}  // namespace rtiow
