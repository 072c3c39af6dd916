// The image backend over OpenImageIO, built as its own shared library
// (librtiow_image_io.so) and loaded on demand by core/io/image_backend.cpp. This is the one
// file of rtiow that includes OpenImageIO.

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "core/io/image_backend.h"
#include "core/io/image_file.h"
#include "core/parallel/thread_probe.h"

namespace rtiow {
namespace {

OIIO::TypeDesc to_oiio(PixelType type) {
  switch (type) {
    case PixelType::UInt8:
      return OIIO::TypeDesc::UINT8;
    case PixelType::UInt16:
      return OIIO::TypeDesc::UINT16;
    case PixelType::UInt32:
      return OIIO::TypeDesc::UINT;
    case PixelType::Half:
      return OIIO::TypeDesc::HALF;
    case PixelType::Float:
      break;
  }
  return OIIO::TypeDesc::FLOAT;
}

PixelType from_oiio(OIIO::TypeDesc type) {
  switch (type.basetype) {
    case OIIO::TypeDesc::UINT8:
    case OIIO::TypeDesc::INT8:
      return PixelType::UInt8;
    case OIIO::TypeDesc::UINT16:
    case OIIO::TypeDesc::INT16:
      return PixelType::UInt16;
    case OIIO::TypeDesc::UINT32:
    case OIIO::TypeDesc::INT32:
    case OIIO::TypeDesc::UINT64:
    case OIIO::TypeDesc::INT64:
      return PixelType::UInt32;
    case OIIO::TypeDesc::HALF:
      return PixelType::Half;
    default:
      return PixelType::Float;
  }
}

// Quiets stderr while alive: libpng prints its own complaint about a truncated or corrupt
// file, and the error line rtiow prints (with the same reason, from OpenImageIO) is to be
// the only one. rtiow reads and writes images only where no other thread prints.
class QuietStderr {
 public:
  QuietStderr() : saved_(::dup(STDERR_FILENO)) {
    const int null = ::open("/dev/null", O_WRONLY);
    if (null >= 0) {
      ::dup2(null, STDERR_FILENO);
      ::close(null);
    }
  }
  ~QuietStderr() {
    if (saved_ >= 0) {
      ::dup2(saved_, STDERR_FILENO);
      ::close(saved_);
    }
  }
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;

 private:
  int saved_;
};

// OpenImageIO keeps the last error per thread until it is read: read it, always, so that a
// stale error never shows up in a later message.
// Its messages may hold several lines (one per complaint): joined with "; ", and a line that
// repeats one already taken is dropped.
std::string take_error(const std::string& first = {}) {
  const std::string global = OIIO::geterror();
  const std::string& text = first.empty() ? global : first;
  std::string joined;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    if (!line.empty() && joined.find(line) == std::string::npos) {
      joined += (joined.empty() ? "" : "; ") + line;
    }
    start = end + 1;
  }
  return joined;
}

OIIO::ImageSpec to_spec(const ImageHeader& header) {
  OIIO::ImageSpec spec(header.width, header.height, int(header.channel_names.size()),
                       OIIO::TypeDesc::FLOAT);
  spec.channelnames = header.channel_names;
  spec.channelformats.clear();
  bool mixed = false;
  for (const PixelType t : header.channel_types) mixed |= t != header.channel_types.front();
  if (mixed) {
    for (const PixelType t : header.channel_types) spec.channelformats.push_back(to_oiio(t));
  }
  spec.format = to_oiio(header.channel_types.front());
  // A crop: the data window at its place, the display window the whole frame.
  spec.x = header.x, spec.y = header.y;
  if (header.full_width > 0 && header.full_height > 0) {
    spec.full_x = 0, spec.full_y = 0;
    spec.full_width = header.full_width, spec.full_height = header.full_height;
  }
  // OpenImageIO stamps EXR and TIFF files with the time of writing unless given a DateTime;
  // an empty one writes none. rtiow's files carry no wall-clock date (the render's time is
  // rtiow:render_seconds, left out by --reproducible), so one job gives one file, byte for
  // byte, in every format.
  spec.attribute("DateTime", std::string());
  for (const ImageAttribute& a : header.attributes) {
    if (const auto* i = std::get_if<int>(&a.value)) {
      spec.attribute(a.name, *i);
    } else if (const auto* f = std::get_if<float>(&a.value)) {
      spec.attribute(a.name, *f);
    } else {
      spec.attribute(a.name, std::get<std::string>(a.value));
    }
  }
  return spec;
}

ImageHeader to_header(const OIIO::ImageSpec& spec) {
  ImageHeader header;
  header.width = spec.width, header.height = spec.height;
  header.x = spec.x, header.y = spec.y, header.depth = spec.depth;
  header.full_width = spec.full_width, header.full_height = spec.full_height;
  header.channel_names = spec.channelnames;
  for (int c = 0; c < spec.nchannels; ++c) {
    header.channel_types.push_back(from_oiio(spec.channelformat(c)));
  }
  for (const auto& attribute : spec.extra_attribs) {
    ImageAttribute a{attribute.name().string(), 0};
    if (attribute.type() == OIIO::TypeDesc::FLOAT) {
      a.value = attribute.get_float();
    } else if (attribute.type() == OIIO::TypeDesc::INT) {
      a.value = attribute.get_int();
    } else {
      a.value = attribute.get_string();
    }
    header.attributes.push_back(std::move(a));
  }
  return header;
}

class OiioImageReader final : public ImageReader {
 public:
  explicit OiioImageReader(std::unique_ptr<OIIO::ImageInput> in)
      : in_(std::move(in)), header_(to_header(in_->spec())) {}

  const ImageHeader& header() const override { return header_; }

  bool read_pixels(PixelType type, void* pixels, std::string& reason) override {
    const int channels = in_->spec().nchannels;
    const QuietStderr quiet;
    if (in_->read_image(0, 0, 0, channels, to_oiio(type), pixels)) return true;
    reason = take_error(in_->geterror());
    return false;
  }

  bool read_rows(PixelType type, int y_begin, int y_end, void* pixels,
                 std::string& reason) override {
    const OIIO::ImageSpec& spec = in_->spec();
    const QuietStderr quiet;
    if (in_->read_scanlines(0, 0, spec.y + y_begin, spec.y + y_end, spec.z, 0, spec.nchannels,
                            to_oiio(type), pixels))
      return true;
    reason = take_error(in_->geterror());
    return false;
  }

 private:
  std::unique_ptr<OIIO::ImageInput> in_;
  ImageHeader header_;
};

// Rows an image is encoded and checked by: a strip's pixels, not the image's, are held beside
// the encoded bytes. A multiple of the 16 rows EXR's zip compresses together.
constexpr int kRowsPerStrip = 64;

// Whether `bytes`, encoded for `path`'s format, decode to all their pixels again (a strip at
// a time): some encoders (PNG in OpenImageIO 2.4) do not report every failure.
bool decodes(const std::string& path, const std::vector<unsigned char>& bytes,
             std::string& reason) {
  OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
  auto in = OIIO::ImageInput::open(path, nullptr, &memory);
  bool whole = in != nullptr;
  if (whole) {
    const OIIO::ImageSpec& spec = in->spec();
    std::vector<float> strip(std::size_t(spec.width) *
                             std::size_t(std::min(kRowsPerStrip, spec.height)) *
                             std::size_t(spec.nchannels));
    for (int y = 0; whole && y < spec.height; y += kRowsPerStrip) {
      whole =
          in->read_scanlines(0, 0, spec.y + y, spec.y + std::min(spec.height, y + kRowsPerStrip),
                             spec.z, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, strip.data());
    }
  }
  if (whole) return true;
  reason = "the encoded image does not decode again: " + take_error();
  return false;
}

class OiioImageBackend final : public ImageBackend {
 public:
  // OpenImageIO's pool and OpenEXR's start their threads the first time a file wants them, and a
  // pool that cannot start them all ends the process (a running thread destroyed) or hangs
  // joining them (issue 69). Where the threads both would take (one per core each, and a
  // spare) cannot all start now, the library does its work on the calling thread alone.
  OiioImageBackend() {
    const int pools = 2 * int(std::max(1u, std::thread::hardware_concurrency())) + 1;
    if (threads_that_can_start_together(pools) < pools) {
      OIIO::attribute("threads", 1);
      OIIO::attribute("exr_threads", -1);
    }
  }

  bool encode(const std::string& path, const ImageHeader& header, const ImageRows& rows,
              std::vector<unsigned char>& bytes, std::string& reason) const override {
    const QuietStderr quiet;
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
      reason = take_error();
      return false;
    }
    // Encoded in memory: a codec never touches the disk, so a full disk or a file-size limit
    // is an error rtiow reports, not a library's exit(1) (libjpeg's default on a failed
    // write), and no codec ever opens a path someone could have put a link at.
    bytes.clear();
    OIIO::Filesystem::IOVecOutput memory(bytes);
    OIIO::ImageSpec spec = to_spec(header);
    void* proxy = &memory;
    spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    // UNKNOWN: the rows hold each channel in its own stored type.
    bool encoded = out->open(path, spec);
    for (int y = 0; encoded && y < header.height; y += kRowsPerStrip) {
      const int end = std::min(header.height, y + kRowsPerStrip);
      encoded =
          out->write_scanlines(spec.y + y, spec.y + end, 0, OIIO::TypeDesc::UNKNOWN, rows(y, end));
    }
    encoded = encoded && out->close();
    if (!encoded) {
      reason = take_error(out->geterror());
      return false;
    }
    return decodes(path, bytes, reason);
  }

  std::unique_ptr<ImageReader> open(const std::string& path, const std::string& format,
                                    std::string& reason) const override {
    const QuietStderr quiet;
    // The reader of the format the file's first bytes named (core/io/image_signature.h): no
    // other reader is tried, so a file that is no image costs one header's read.
    auto in = OIIO::ImageInput::create(format);
    if (!in) {
      reason = take_error();
      return nullptr;
    }
    OIIO::ImageSpec spec;
    if (!in->open(path, spec)) {
      reason = take_error(in->geterror());
      return nullptr;
    }
    return std::make_unique<OiioImageReader>(std::move(in));
  }
};

}  // namespace
}  // namespace rtiow

extern "C" __attribute__((visibility("default"))) const rtiow::ImageBackend* rtiow_image_backend(
    int abi_version) {
  static const rtiow::OiioImageBackend backend;
  return abi_version == rtiow::kImageBackendAbi ? &backend : nullptr;
}
