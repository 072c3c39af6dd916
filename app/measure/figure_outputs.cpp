#include "app/measure/figure_outputs.h"

#include <unistd.h>

#include <filesystem>

#include "core/io/output_claim.h"
#include "core/io/output_path.h"
#include "core/limits/error.h"

namespace rtiow {

namespace fs = std::filesystem;

FigureOutputs::FigureOutputs(const std::string& directory, const std::vector<std::string>& names,
                             const std::string& option)
    : directory_(directory) {
  check_output_directory(directory, option);
  std::error_code error;
  made_directory_ = fs::create_directories(directory, error);
  if (error) {
    throw InvalidInput(option + " " + quote_value(directory) +
                       ": cannot make the directory: " + error.message());
  }
  try {
    for (const std::string& name : names) {
      check_output_path(path(name), {}, option.c_str());
      claims_.push_back(std::make_unique<OutputClaim>(path(name)));
    }
  } catch (...) {
    claims_.clear();
    if (made_directory_) ::rmdir(directory.c_str());
    throw;
  }
}

FigureOutputs::~FigureOutputs() {
  claims_.clear();  // the locks go first
  // Only if it is still empty: rmdir removes nothing else.
  if (made_directory_) ::rmdir(directory_.c_str());
}

std::string FigureOutputs::path(const std::string& name) const {
  return (fs::path(directory_) / name).string();
}

}  // namespace rtiow
