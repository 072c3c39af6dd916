#pragma once
// Writing a file so that it is never seen half-written: the content goes to a temporary
// beside the target (same directory, so the rename stays on one file system and is atomic)
// and is renamed over the target only when complete. On failure the temporary is removed
// and the target is left as it was.

#include <functional>
#include <string>

namespace rtiow {

// Calls `write(temporary_path)`, which returns false (and sets `reason`) or throws on failure.
// The temporary keeps the target's extension, for writers that pick a format by it.
// Throws std::runtime_error "cannot write 'path': reason".
void write_atomically(
    const std::string& path,
    const std::function<bool(const std::string& temporary, std::string& reason)>& write);

// The same for text.
void write_text_atomically(const std::string& path, const std::string& text);

}  // namespace rtiow
