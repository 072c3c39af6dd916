#include "core/io/output_path.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/io/input_file.h"
#include "core/limits/error.h"

namespace rtiow {
namespace {

namespace fs = std::filesystem;

// OpenImageIO also knows pseudo-formats that print to a terminal ("term") or discard the
// image ("null"), and formats that cannot hold RGB as rtiow writes it: only these are real.
// (PFM is not here: Debian's OpenImageIO 2.4 reads it but has no writer.)
constexpr std::array<ImageFormat, 10> kFormats{{
    {".png", false, false, true, Provenance::Attributes, false},
    {".jpg", false, false, false, Provenance::Description, false},
    {".jpeg", false, false, false, Provenance::Description, false},
    {".ppm", false, false, false, Provenance::None, false},
    {".bmp", false, false, false, Provenance::None, false},
    {".tga", false, false, false, Provenance::None, false},
    {".tif", false, false, false, Provenance::Description, false},
    {".tiff", false, false, false, Provenance::Description, false},
    {".exr", true, true, false, Provenance::Attributes, true},
    {".hdr", true, false, false, Provenance::None, false},
}};

// Room for what rtiow adds to a name: a checkpoint's ".rtiow-checkpoint", and a temporary's "."
// and ".rtiow-tmp-" with 8 letters (237 bytes at most, under the 255 a name may have).
constexpr std::size_t kMaxFileNameBytes = 200;
constexpr std::size_t kMaxPathBytes = 3000;

std::string lowercase_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

}  // namespace

bool is_own_file_name(const std::string& file_name) {
  const auto ends_with = [&](std::string_view end) { return file_name.ends_with(end); };
  return (file_name.starts_with(".") && ends_with(kLockSuffix)) ||
         file_name.find(kTemporaryMark) != std::string::npos || ends_with(kCheckpointSuffix);
}

const ImageFormat* image_format(const std::string& path) {
  const std::string ext = lowercase_extension(path);
  for (const ImageFormat& f : kFormats) {
    if (ext == f.extension) return &f;
  }
  return nullptr;
}

std::string image_extensions() {
  std::string list;
  for (const ImageFormat& f : kFormats) list.append(list.empty() ? "" : " ").append(f.extension);
  return list;
}

namespace {

// The path as a name: not empty, no NUL, a file's name within the limits, none of rtiow's own.
void check_output_name(const std::string& path, const std::string& name, const char* what) {
  if (path.empty()) throw InvalidInput(std::string(what) + ": the path is empty");
  if (path.find('\0') != std::string::npos) throw InvalidInput(name + ": holds a NUL byte");
  const fs::path p(path);
  const std::string file_name = p.filename().string();
  if (file_name.empty() || file_name == "." || file_name == "..") {
    throw InvalidInput(name + ": names a directory, not a file");
  }
  if (file_name.size() > kMaxFileNameBytes) {
    throw InvalidInput(name + ": the file name is longer than " +
                       std::to_string(kMaxFileNameBytes) + " bytes");
  }
  if (path.size() > kMaxPathBytes) {
    throw InvalidInput(name + ": the path is longer than " + std::to_string(kMaxPathBytes) +
                       " bytes");
  }
  if (is_own_file_name(file_name)) {
    throw InvalidInput(name +
                       ": is a name rtiow gives its own files (a lock, a temporary or a "
                       "checkpoint), which a render of that image replaces or removes: choose "
                       "another");
  }
}

// Where it points: a writable directory, and no file there that rtiow must not replace.
void check_output_place(const std::string& path, const std::string& name) {
  const fs::path p(path);
  const fs::path parent = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  struct stat info {};
  if (::stat(parent.c_str(), &info) != 0 || !S_ISDIR(info.st_mode)) {
    throw InvalidInput(name + ": directory " + quote_value(parent.string()) + " does not exist");
  }
  if (::access(parent.c_str(), W_OK | X_OK) != 0) {
    throw InvalidInput(name + ": directory " + quote_value(parent.string()) +
                       " is not writable: " + std::strerror(errno));
  }
  const struct stat directory = info;
  // In a sticky directory (/tmp and its like) only the owner of a name, or of the directory,
  // may rename over it or remove it: found here, not after the work.
  struct stat entry {};
  const uid_t me = ::geteuid();
  if ((directory.st_mode & S_ISVTX) && me != 0 && directory.st_uid != me &&
      ::lstat(path.c_str(), &entry) == 0 && entry.st_uid != me) {
    throw InvalidInput(name +
                       ": is another user's file in a sticky directory (like /tmp), which "
                       "only its owner can replace: choose another name");
  }
  if (::stat(path.c_str(), &info) == 0) {
    if (S_ISDIR(info.st_mode)) throw InvalidInput(name + ": is a directory");
    if (!S_ISREG(info.st_mode)) {
      throw InvalidInput(name + ": is not a regular file (a device, FIFO or socket)");
    }
    // Replaced by rename, which would succeed over a read-only file: its mode says to keep it.
    if ((info.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0 || ::access(path.c_str(), W_OK) != 0) {
      throw InvalidInput(name +
                         ": is read-only to you: rtiow does not replace it (make it "
                         "writable, or choose another name)");
    }
  }
}

}  // namespace

void check_output_path(const std::string& path, const std::vector<std::string>& inputs,
                       const char* what) {
  const std::string name = std::string(what) + " " + quote_value(path);
  check_output_name(path, name, what);
  check_output_place(path, name);
  for (const std::string& input : inputs) {
    if (same_file(path, input)) {
      throw InvalidInput(name + ": is the input file " + quote_value(input) +
                         "; writing it would destroy it");
    }
  }
}

void check_image_output(const std::string& path, const std::vector<std::string>& inputs,
                        bool extra_channels) {
  check_output_path(path, inputs);
  const ImageFormat* format = image_format(path);
  if (!format) {
    throw InvalidInput("output " + quote_value(path) + ": not an image format rtiow writes (" +
                       image_extensions() + ")");
  }
  if (extra_channels && !format->extra_channels) {
    throw InvalidInput("output " + quote_value(path) +
                       ": extra channels need a format that holds them (.exr)");
  }
}

std::string partial_output_path(const std::string& output) {
  fs::path p(output);
  const std::string extension = p.extension().string();
  p.replace_filename(p.stem().string() + ".partial" + extension);
  return p.string();
}

std::string safe_file_stem(const std::string& scene_name) {
  constexpr std::size_t kMaxStem = 64;
  std::string stem;
  for (const char c : scene_name) {
    if (stem.size() == kMaxStem) break;
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                       c == '.' || c == '_' || c == '-';
    stem += plain ? c : '-';
  }
  // No leading dot (a hidden file) or dash (read as an option by other tools).
  while (!stem.empty() && (stem.front() == '.' || stem.front() == '-')) stem.erase(stem.begin());
  return stem.empty() ? "render" : stem;
}

void check_output_directory(const std::string& path, const std::string& what) {
  if (path.empty()) throw InvalidInput(what + ": the path is empty");
  std::error_code error;
  if (std::filesystem::exists(path, error) && !std::filesystem::is_directory(path, error)) {
    throw InvalidInput(what + " " + quote_value(path) + ": is not a directory");
  }
}

}  // namespace rtiow
