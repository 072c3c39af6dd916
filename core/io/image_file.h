#pragma once
// Image files as rtiow reads and writes them, in words that name no image library: a
// header (size, channels, attributes) and interleaved pixels. The one implementation,
// over OpenImageIO, lives in a shared library of its own (core/io/oiio_image_backend.cpp)
// that is loaded only when an image is read or written (core/io/image_backend.h): Debian's
// OpenImageIO pulls in some 260 shared libraries, and a command that writes no image
// should not wait for them.
//
// The types cross that library boundary, so they are plain: no exceptions are thrown across
// it (failures come back as false and a reason).

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace rtiow {

// How one channel's values are stored (in a file, or in a buffer handed over). Integers of a
// width are one type whatever their sign; double is read as Float.
enum class PixelType { UInt8, UInt16, UInt32, Half, Float };

struct ImageAttribute {
  std::string name;
  std::variant<int, float, std::string> value;
};

struct ImageHeader {
  int width = 0, height = 0;
  // The data window and the display window, where a format has them: rtiow writes and
  // accepts only x = y = 0, depth 1, full size = size.
  int x = 0, y = 0, depth = 1, full_width = 0, full_height = 0;
  std::vector<std::string> channel_names;
  std::vector<PixelType> channel_types;  // when writing: how each channel is stored
  std::vector<ImageAttribute> attributes;

  // The value of a string attribute; "" when absent or not a string.
  std::string string_attribute(const std::string& name) const {
    for (const ImageAttribute& a : attributes) {
      if (a.name != name) continue;
      if (const auto* s = std::get_if<std::string>(&a.value)) return *s;
    }
    return {};
  }
};

// An image file opened for reading: its header first, so that callers can check the size
// before allocating anything, then all of its pixels.
class ImageReader {
 public:
  virtual ~ImageReader() = default;
  virtual const ImageHeader& header() const = 0;
  // Every channel of every pixel, converted to `type`, interleaved, row major; `pixels`
  // must hold width * height * channels values. False (and `reason`) on failure.
  virtual bool read_pixels(PixelType type, void* pixels, std::string& reason) = 0;
  // The same for the rows [y_begin, y_end) alone (0 <= y_begin < y_end <= height): `pixels`
  // holds width * (y_end - y_begin) * channels values. What reads a large image a strip at a
  // time, so that it never holds every pixel's channels at once.
  virtual bool read_rows(PixelType type, int y_begin, int y_end, void* pixels,
                         std::string& reason) = 0;
};

// The rows [y_begin, y_end) of an image being encoded, interleaved in its header's channel
// types: an encoder asks for them a strip at a time, top to bottom, so whoever makes the pixels
// (a part file's 268 bytes a pixel) need not hold them all at once. What it returns stays valid
// until the next call.
using ImageRows = std::function<const void*(int y_begin, int y_end)>;

class ImageBackend {
 public:
  virtual ~ImageBackend() = default;
  // Encodes the image `rows` gives in memory in the format the extension of `path` names, and
  // checks that the bytes decode again (some encoders do not report a failure). The backend
  // never writes a file: rtiow writes the bytes itself (core/io/atomic_file.h). False (and
  // `reason`) on failure.
  virtual bool encode(const std::string& path, const ImageHeader& header, const ImageRows& rows,
                      std::vector<unsigned char>& bytes, std::string& reason) const = 0;
  // Nothing (and `reason`) when the file does not open as an image of `format` (OpenImageIO's
  // name for it, from core/io/image_signature.h: the file's first bytes chose it). `path` may
  // name an open descriptor (/proc/self/fd/N).
  virtual std::unique_ptr<ImageReader> open(const std::string& path, const std::string& format,
                                            std::string& reason) const = 0;
};

}  // namespace rtiow
