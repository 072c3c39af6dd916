#include "core/io/image_signature.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>

namespace rtiow {
namespace {

bool starts_with(const std::string& bytes, const char* signature, std::size_t size) {
  return bytes.size() >= size && std::memcmp(bytes.data(), signature, size) == 0;
}

unsigned byte(const std::string& bytes, std::size_t at) {
  return at < bytes.size() ? static_cast<unsigned char>(bytes[at]) : 0u;
}

// "P1".."P7" or "PF"/"Pf" and then white space.
bool is_pnm(const std::string& b) {
  if (b.size() < 3 || b[0] != 'P') return false;
  const bool kind = (b[1] >= '1' && b[1] <= '7') || b[1] == 'F' || b[1] == 'f';
  return kind && std::isspace(static_cast<unsigned char>(b[2]));
}

// "BM" and a DIB header of one of the sizes the format defines.
bool is_bmp(const std::string& b) {
  if (!starts_with(b, "BM", 2)) return false;
  const unsigned dib = byte(b, 14) | byte(b, 15) << 8 | byte(b, 16) << 16 | byte(b, 17) << 24;
  return dib == 12 || dib == 40 || dib == 52 || dib == 56 || dib == 64 || dib == 108 || dib == 124;
}

// TGA has no signature: a .tga name and a header whose fields hold values TGA defines.
bool is_tga(const std::string& b, const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".tga" || b.size() < 18) return false;
  const unsigned map = byte(b, 1), type = byte(b, 2), bits = byte(b, 16);
  const bool type_ok = type == 1 || type == 2 || type == 3 || type == 9 || type == 10 || type == 11;
  const bool bits_ok = bits == 8 || bits == 15 || bits == 16 || bits == 24 || bits == 32;
  return map <= 1 && type_ok && bits_ok;
}

}  // namespace

std::string image_format_of(const std::string& first, const std::string& path) {
  if (starts_with(first, "\x89PNG\r\n\x1a\n", 8)) return "png";
  if (starts_with(first, "\x76\x2f\x31\x01", 4)) return "openexr";
  if (starts_with(first, "\xff\xd8\xff", 3)) return "jpeg";
  if (starts_with(first, "II*\0", 4) || starts_with(first, "MM\0*", 4) ||
      starts_with(first, "II+\0", 4) || starts_with(first, "MM\0+", 4)) {
    return "tiff";
  }
  if (starts_with(first, "#?", 2)) return "hdr";  // #?RADIANCE, #?RGBE
  if (is_pnm(first)) return "pnm";
  if (is_bmp(first)) return "bmp";
  if (is_tga(first, path)) return "targa";
  return {};
}

const char* readable_image_formats() {
  return "PNG, OpenEXR, JPEG, TIFF, BMP, PNM/PFM, Radiance HDR or TGA";
}

}  // namespace rtiow
