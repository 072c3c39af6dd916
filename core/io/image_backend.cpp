#include "core/io/image_backend.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <future>
#include <mutex>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>

#include "core/io/image_expansion.h"
#include "core/io/image_file.h"
#include "core/io/image_signature.h"
#include "core/io/input_file.h"
#include "core/limits/error.h"
#include "core/limits/input_limits.h"
#include "core/parallel/thread_probe.h"

#ifndef RTIOW_LIBDIR_FROM_BINDIR
#define RTIOW_LIBDIR_FROM_BINDIR "../lib"
#endif

namespace rtiow {
namespace {

using Entry = const ImageBackend* (*)(int abi_version);
constexpr const char* kEntryName = "rtiow_image_backend";

}  // namespace
}  // namespace rtiow

// Defined when the backend is linked in statically (an installed rtiow's programs link its
// static archive), else null: then it is found loaded, or loaded.
extern "C" __attribute__((weak)) const rtiow::ImageBackend* rtiow_image_backend(int abi_version);

namespace rtiow {
namespace {

struct Loaded {
  const ImageBackend* backend = nullptr;
  std::string error;
};

Loaded from_entry(Entry entry, const std::string& where) {
  const ImageBackend* backend = entry(kImageBackendAbi);
  if (!backend) return {nullptr, where + " is from another build of rtiow"};
  return {backend, {}};
}

Loaded try_open(const std::string& path) {
  // Kept open for the life of the process: the backend's objects live in it.
  void* library = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!library) {
    // There but not loadable (no memory for it, a broken install): say why, in the loader's
    // words. Not there: look further.
    const char* why = ::dlerror();
    std::error_code error;
    if (path.find('/') == std::string::npos || !std::filesystem::exists(path, error)) return {};
    return {nullptr, "cannot read or write images: cannot load " + path + ": " +
                         (why ? why : "the loader gave no reason")};
  }
  void* entry = ::dlsym(library, kEntryName);
  if (!entry) return {nullptr, path + " has no " + kEntryName};
  return from_entry(reinterpret_cast<Entry>(entry), path);
}

std::string beside_program() {
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return {};
  return (program.parent_path() / RTIOW_LIBDIR_FROM_BINDIR / kImageBackendFile)
      .lexically_normal()
      .string();
}

Loaded linked() {
  if (&rtiow_image_backend != nullptr) {
    return from_entry(&rtiow_image_backend, "the linked backend");
  }
  if (void* entry = ::dlsym(RTLD_DEFAULT, kEntryName))
    return from_entry(reinterpret_cast<Entry>(entry), "the linked backend");
  return {};
}

// The image library starts threads as it loads (log4cplus's pool, 4 on 2 cores, under
// OpenImageIO's DICOM reader; OpenEXR's, one per core) and, when one cannot start, ends the
// process from inside the loader or hangs joining the others, where nothing can catch it
// (issue 69). So as many as that are tried first (one more for a load on a thread of its
// own): why they cannot all start, or "".
std::string threads_shortfall(bool in_background = false) {
  const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
  const int needed = std::max(4, cores) + cores + 1 + (in_background ? 1 : 0);
  int error = 0;
  const int started = threads_that_can_start_together(needed, &error);
  if (started == needed) return "";
  return "cannot read or write images: the image library starts " + std::to_string(needed) +
         " threads as it loads, and " + std::to_string(started) +
         " could start now: " + system_error_text(error);
}

Loaded load() {
  if (Loaded found = linked(); found.backend) return found;
  if (std::string why = threads_shortfall(); !why.empty()) return {nullptr, why};
  const std::string local = beside_program();
  std::string looked;
  if (!local.empty()) {
    Loaded found = try_open(local);
    if (found.backend || !found.error.empty()) return found;
    looked = local + ", ";
  }
  Loaded found = try_open(kImageBackendFile);
  if (found.backend || !found.error.empty()) return found;
  return {nullptr, std::string("cannot read or write images: ") + kImageBackendFile +
                       " (rtiow's OpenImageIO module) was not found (looked at " + looked +
                       "and the library path); a program built with find_package(rtiow) writes "
                       "PNG by itself and links rtiow::image_io for every other format"};
}

std::once_flag started;
std::shared_future<Loaded> loading;

const ImageBackend& loaded_backend() {
  const Loaded& loaded = loading.get();
  if (!loaded.backend) throw std::runtime_error(loaded.error);
  return *loaded.backend;
}

}  // namespace

void preload_image_backend() {
  std::call_once(started, [] {
    // In the background only where it will be found: otherwise load now, so that a missing
    // backend is reported before a render rather than after it.
    std::error_code error;
    const bool beside = std::filesystem::exists(beside_program(), error);
    // Threads short: loaded (and refused) now, before the work, not at its end.
    const bool in_background = beside && !linked().backend && threads_shortfall(true).empty();
    const auto policy = in_background ? std::launch::async : std::launch::deferred;
    try {
      loading = std::async(policy, load).share();
    } catch (const std::system_error&) {
      // No thread to be had (a memory or process limit): load when the image is written.
      loading = std::async(std::launch::deferred, load).share();
    }
  });
  if (loading.wait_for(std::chrono::seconds(0)) == std::future_status::deferred) loaded_backend();
}

const ImageBackend& image_backend() {
  std::call_once(started, [] { loading = std::async(std::launch::deferred, load).share(); });
  return loaded_backend();
}

namespace {

// The library's reason, with the descriptor's name it was given spelt as the user's path.
std::string in_words_of(std::string reason, const std::string& library_name,
                        const std::string& path) {
  for (std::size_t at = reason.find(library_name); at != std::string::npos;
       at = reason.find(library_name, at + path.size())) {
    reason.replace(at, library_name.size(), path);
  }
  return reason.empty() ? "the image library gives no reason" : reason;
}

// A reader that holds the file it reads open (the library reopened it by its descriptor's
// name) and speaks of it by the user's path.
class CheckedImageReader final : public ImageReader {
 public:
  CheckedImageReader(InputFile file, std::string path, std::unique_ptr<ImageReader> in)
      : file_(std::move(file)), path_(std::move(path)), in_(std::move(in)) {}
  const ImageHeader& header() const override { return in_->header(); }
  bool read_pixels(PixelType type, void* pixels, std::string& reason) override {
    if (in_->read_pixels(type, pixels, reason)) return true;
    reason = in_words_of(reason, file_.name_for_library(), path_);
    return false;
  }
  bool read_rows(PixelType type, int y_begin, int y_end, void* pixels,
                 std::string& reason) override {
    if (in_->read_rows(type, y_begin, y_end, pixels, reason)) return true;
    reason = in_words_of(reason, file_.name_for_library(), path_);
    return false;
  }

 private:
  InputFile file_;
  std::string path_;
  std::unique_ptr<ImageReader> in_;
};

}  // namespace

namespace {

std::uint64_t bytes_of(PixelType type) {
  switch (type) {
    case PixelType::UInt8:
      return 1;
    case PixelType::UInt16:
    case PixelType::Half:
      return 2;
    case PixelType::UInt32:
    case PixelType::Float:
      break;
  }
  return 4;
}

// Why the header's declared size is not an image rtiow reads from a file of `file_bytes`, or "".
std::string why_not_readable(const ImageHeader& header, std::uint64_t file_bytes,
                             const std::string& format) {
  const auto size = std::to_string(header.width) + "x" + std::to_string(header.height);
  if (header.width < 1 || header.height < 1 || header.width > limits::kMaxImageSide ||
      header.height > limits::kMaxImageSide) {
    return "its header says " + size + ", outside 1 to " + std::to_string(limits::kMaxImageSide) +
           " pixels a side";
  }
  const std::uint64_t pixels = std::uint64_t(header.width) * std::uint64_t(header.height);
  if (pixels > limits::kMaxPixels) {
    return "its header says " + size + ", more than " + std::to_string(limits::kMaxPixels) +
           " pixels";
  }
  const std::size_t channels = header.channel_names.size();
  if (channels < 1 || channels > limits::kMaxImageChannels ||
      header.channel_types.size() != channels) {
    return "its header says " + std::to_string(channels) + " channels, outside 1 to " +
           std::to_string(limits::kMaxImageChannels);
  }
  std::uint64_t pixel_bytes = 0;
  for (const PixelType type : header.channel_types) pixel_bytes += bytes_of(type);
  const std::uint64_t declared = pixels * pixel_bytes;
  const std::uint64_t expansion = max_expansion(format, header.string_attribute("compression"));
  const std::uint64_t holdable = std::max(limits::kImageBytesAlwaysRead, file_bytes * expansion);
  if (declared > holdable) {
    return "its header says " + size + " with " + std::to_string(channels) + " channels (" +
           std::to_string(declared >> 20) + " MiB of pixels), more than a " + format + " file of " +
           std::to_string(file_bytes) + " bytes can hold (at most " + std::to_string(expansion) +
           " times its size, its format's best compression)";
  }
  return {};
}

// The backend opens the file again by name and silences stderr meanwhile (three descriptors
// at once): a process without them would see the file refused as "not an image", which is no
// fault of the file's. Said as what it is instead.
void require_spare_descriptors(const std::string& name) {
  constexpr int kNeeded = 3;
  int spare[kNeeded];
  int held = 0;
  int error = 0;
  for (; held < kNeeded; ++held) {
    spare[held] = ::fcntl(STDIN_FILENO, F_DUPFD_CLOEXEC, 0);
    if (spare[held] < 0) {
      error = errno;
      break;
    }
  }
  for (int i = 0; i < held; ++i) ::close(spare[i]);
  if (error != 0) throw std::runtime_error("cannot read " + name + ": " + system_error_text(error));
}

}  // namespace

std::unique_ptr<ImageReader> open_input_image(const std::string& path, const std::string& name,
                                              std::uint64_t max_bytes, const char* what,
                                              InputKind kind) {
  InputFile file(path, max_bytes, what, kind);
  const std::string format = image_format_of(file.first_bytes(kImageSignatureBytes), path);
  if (format.empty()) {
    throw InvalidInput(name + ": is not an image rtiow reads: its first bytes are no " +
                       readable_image_formats() + " signature");
  }
  if (format == "pnm") {  // its header checked here: the library reads on until it finds one
    const std::string why = why_not_a_pnm_image(file.first_bytes(kPnmHeaderBytes), file.size());
    if (!why.empty()) throw InvalidInput(name + ": " + why);
  }
  const std::string library_name = file.name_for_library();
  std::string reason;
  require_spare_descriptors(name);
  auto in = image_backend().open(library_name, format, reason);
  if (!in) {
    throw InvalidInput(name +
                       ": cannot read: " + one_line(in_words_of(reason, library_name, path), 200));
  }
  const std::string why = why_not_readable(in->header(), file.size(), format);
  if (!why.empty()) throw InvalidInput(name + ": " + why);
  return std::make_unique<CheckedImageReader>(std::move(file), path, std::move(in));
}

}  // namespace rtiow
