#include "core/io/atomic_file.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace rtiow {

void write_atomically(
    const std::string& path,
    const std::function<bool(const std::string& temporary, std::string& reason)>& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  std::string name = ".";
  name.append(target.stem().string())
      .append(".tmp-")
      .append(std::to_string(::getpid()))
      .append(target.extension().string());
  const fs::path temporary = target.parent_path() / name;
  std::string reason;
  bool written = false;
  try {
    written = write(temporary.string(), reason);
  } catch (const std::exception& e) {
    reason = e.what();
  }
  std::error_code error;
  if (written) fs::rename(temporary, target, error);
  if (!written || error) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw std::runtime_error("cannot write '" + path +
                             "': " + (written ? error.message() : reason));
  }
}

void write_text_atomically(const std::string& path, const std::string& text) {
  write_atomically(path, [&](const std::string& temporary, std::string& reason) {
    std::ofstream out(temporary, std::ios::binary);
    out << text;
    out.close();
    if (!out) reason = "write failed";
    return bool(out);
  });
}

}  // namespace rtiow
