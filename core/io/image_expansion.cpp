#include "core/io/image_expansion.h"

#include <cctype>
#include <optional>
#include <vector>

#include "core/limits/input_limits.h"

namespace rtiow {

std::uint64_t max_expansion(const std::string& format, const std::string& compression) {
  if (format == "png") return 1100;   // deflate: at most 1032 bytes out of one byte in
  if (format == "jpeg") return 1024;  // an 8x8 block of one colour in a few bits
  if (format == "tiff") return 4096;  // LZW's longest strings, deflate's 1032
  if (format == "hdr") return 256;    // runs of 127 in 2 bytes, 12 bytes of floats from 4
  if (format == "bmp" || format == "targa") return 128;  // run lengths
  if (format == "pnm") return 8;                         // a bitmap: one bit a pixel
  if (format == "openexr") {
    const std::string kind = compression.substr(0, compression.find(':'));
    if (kind == "none") return 2;
    if (kind == "rle") return 128;
    if (kind == "zip" || kind == "zips" || kind == "pxr24") return 1400;  // deflate; pxr24 3/4
    if (kind == "piz") return 4096;
    if (kind == "b44" || kind == "b44a") return 64;
  }
  return 65536;  // DWAA/DWAB (a block's DC, deflated) and anything not named
}

namespace {

// Reads PNM header tokens: white space and '#' comments between them.
class PnmTokens {
 public:
  explicit PnmTokens(const std::string& bytes) : bytes_(bytes) {}

  // The next decimal number, or nothing (not a digit, too long, or the bytes end first).
  std::optional<std::uint64_t> number() {
    skip_space();
    std::uint64_t value = 0;
    std::size_t digits = 0;
    while (at_ < bytes_.size() && std::isdigit(static_cast<unsigned char>(bytes_[at_]))) {
      if (++digits > 12) return std::nullopt;
      value = value * 10 + std::uint64_t(bytes_[at_++] - '0');
    }
    if (digits == 0 || at_ >= bytes_.size()) return std::nullopt;  // the header must end
    return value;
  }

  // A PFM scale: an optional sign, digits and a point.
  bool scale() {
    skip_space();
    const std::size_t start = at_;
    while (at_ < bytes_.size() &&
           (std::isdigit(static_cast<unsigned char>(bytes_[at_])) || bytes_[at_] == '-' ||
            bytes_[at_] == '+' || bytes_[at_] == '.' || bytes_[at_] == 'e' || bytes_[at_] == 'E')) {
      ++at_;
    }
    return at_ > start && at_ < bytes_.size();
  }

  // Where the pixels start: after the one white space character that ends the header.
  std::size_t data_start() const { return at_ + 1; }

 private:
  void skip_space() {
    while (at_ < bytes_.size()) {
      const char c = bytes_[at_];
      if (c == '#') {
        while (at_ < bytes_.size() && bytes_[at_] != '\n') ++at_;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        ++at_;
      } else {
        return;
      }
    }
  }

  const std::string& bytes_;
  std::size_t at_ = 2;  // after the magic number
};

std::string sized(std::uint64_t width, std::uint64_t height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

}  // namespace

std::string why_not_a_pnm_image(const std::string& first, std::uint64_t file_bytes) {
  const std::string no_header =
      "its PNM header holds no width, height and maximum value in its "
      "first " +
      std::to_string(kPnmHeaderBytes) + " bytes";
  if (first.size() < 3) return no_header;
  const char kind = first[1];
  if (kind == '7') {  // PAM: keyword lines up to ENDHDR
    return first.find("ENDHDR") == std::string::npos
               ? "its PAM header has no ENDHDR in its first " + std::to_string(kPnmHeaderBytes) +
                     " bytes"
               : "";
  }
  PnmTokens tokens(first);
  const std::optional<std::uint64_t> width = tokens.number(), height = tokens.number();
  if (!width || !height) return no_header;
  if (*width < 1 || *height < 1 || *width > std::uint64_t(limits::kMaxImageSide) ||
      *height > std::uint64_t(limits::kMaxImageSide)) {
    return "its header says " + sized(*width, *height) + ", outside 1 to " +
           std::to_string(limits::kMaxImageSide) + " pixels a side";
  }
  std::uint64_t sample_bytes = 1;
  if (kind == 'F' || kind == 'f') {
    if (!tokens.scale()) return no_header;
    sample_bytes = 4;
  } else if (kind != '1' && kind != '4') {
    const std::optional<std::uint64_t> maxval = tokens.number();
    if (!maxval || *maxval < 1 || *maxval > 65535) return no_header;
    sample_bytes = *maxval > 255 ? 2 : 1;
  }
  const std::uint64_t pixels = *width * *height;
  const std::uint64_t channels = (kind == '3' || kind == '6' || kind == 'F') ? 3 : 1;
  // The fewest bytes the pixels take: as they are for the binary kinds; for the text kinds
  // (P1-P3) a character a bit, and a digit and a separator a sample.
  std::uint64_t needed = 0;
  switch (kind) {
    case '1':
      needed = pixels;
      break;
    case '2':
    case '3':
      needed = 2 * pixels * channels - 1;
      break;
    case '4':
      needed = (*width + 7) / 8 * *height;
      break;
    default:
      needed = pixels * channels * sample_bytes;
  }
  const std::uint64_t start = tokens.data_start();
  const std::uint64_t present = file_bytes > start ? file_bytes - start : 0;
  if (present < needed) {
    return "its header says " + sized(*width, *height) + ", whose pixels take at least " +
           std::to_string(needed) + " bytes, but the file holds " + std::to_string(present) +
           " after its header";
  }
  return {};
}

}  // namespace rtiow
