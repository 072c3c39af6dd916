#include "core/measure/figure_outputs.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/io/removed_on_abort.h"
#include "core/limits/error.h"

namespace rtiow {

namespace fs = std::filesystem;

FigureOutputs::FigureOutputs(const std::string& directory, const std::vector<std::string>& names,
                             const std::string& option)
    : directory_(directory) {
  check_output_directory(directory, option);
  try {
    make_directories(option);
    for (const std::string& name : names) {
      check_output_path(path(name), {}, option.c_str());
      claims_.push_back(std::make_unique<OutputClaim>(path(name)));
    }
  } catch (...) {
    claims_.clear();
    remove_made_directories();
    throw;
  }
}

FigureOutputs::~FigureOutputs() {
  claims_.clear();  // the locks go first
  remove_made_directories();
}

void FigureOutputs::make_directories(const std::string& option) {
  // Level by level, from the outermost missing one, so each made is known (and registered to
  // go again should a signal end rtiow before its files are written).
  std::vector<fs::path> missing;
  std::error_code error;
  for (fs::path p = fs::path(directory_).lexically_normal(); !p.empty() && p != p.root_path();
       p = p.parent_path()) {
    if (fs::exists(fs::symlink_status(p, error))) break;
    missing.insert(missing.begin(), p);
    if (!p.has_parent_path()) break;
  }
  for (const fs::path& p : missing) {
    const fs::path parent = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    if (::mkdir(p.c_str(), 0777) != 0) {
      throw InvalidInput(option + " " + quote_value(directory_) + ": cannot make " +
                         quote_value(p.string()) + ": " + std::strerror(errno));
    }
    MadeDirectory made{p.string(), ::open(parent.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC), {}};
    if (made.parent_fd >= 0) {
      made.on_abort = std::make_unique<RemovedOnAbort>(made.parent_fd, p.filename().string(),
                                                       RemovedOnAbort::EmptyDirectory);
    }
    made_.push_back(std::move(made));
  }
}

void FigureOutputs::remove_made_directories() {
  for (auto it = made_.rbegin(); it != made_.rend(); ++it) {
    ::rmdir(it->path.c_str());  // rmdir removes nothing that is not empty
    it->on_abort.reset();
    if (it->parent_fd >= 0) ::close(it->parent_fd);
  }
  made_.clear();
}

std::string FigureOutputs::path(const std::string& name) const {
  return (fs::path(directory_) / name).string();
}

}  // namespace rtiow
