#include "core/io/image_output.h"

#include "core/io/atomic_file.h"
#include "core/io/image_backend.h"
#include "core/io/image_file.h"
#include "core/io/json_writer.h"
#include "core/io/output_path.h"
#include "core/io/png_encoder.h"
#include "core/version.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <vector>

namespace rtiow {
namespace {

namespace fs = std::filesystem;

std::string metadata_string(const MetadataValue& v) {
  if (const auto* i = std::get_if<std::int64_t>(&v)) return std::to_string(*i);
  if (const auto* d = std::get_if<double>(&v)) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.9g", *d);
    return buffer;
  }
  return std::get<std::string>(v);
}

void add_metadata(ImageHeader& header, const Metadata& unordered, bool typed,
                  Provenance provenance) {
  if (provenance == Provenance::None) return;
  // In key order, as EXR itself stores attributes: the same metadata gives the same bytes
  // however it was gathered (a render, or a merge of parts read back from EXR).
  Metadata metadata = unordered;
  std::sort(metadata.begin(), metadata.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [key, value] : metadata) {
    const std::string name = kMetadataPrefix + key;
    if (typed && std::holds_alternative<std::int64_t>(value)) {
      // EXR has no 64-bit integer attribute: larger counts are stored as strings.
      const auto i = std::get<std::int64_t>(value);
      if (i >= INT32_MIN && i <= INT32_MAX) {
        header.attributes.push_back({name, int(i)});
      } else {
        header.attributes.push_back({name, std::to_string(i)});
      }
    } else if (typed && std::holds_alternative<double>(value)) {
      header.attributes.push_back({name, float(std::get<double>(value))});
    } else {
      header.attributes.push_back({name, metadata_string(value)});
    }
  }
  header.attributes.push_back({"Software", std::string("rtiow ") + version()});
  // Every key again as one JSON object in the description, which JPEG (EXIF) and TIFF keep where
  // they drop other attributes.
  if (provenance == Provenance::Description && !metadata.empty()) {
    // A key given twice keeps its first place and its last value.
    Metadata unique;
    for (const auto& entry : metadata) {
      const auto same = std::find_if(unique.begin(), unique.end(),
                                     [&](const auto& u) { return u.first == entry.first; });
      if (same != unique.end()) {
        same->second = entry.second;
      } else {
        unique.push_back(entry);
      }
    }
    JsonWriter all;
    all.begin_object();
    for (const auto& [key, value] : unique) all.key(kMetadataPrefix + key).value(value);
    header.attributes.push_back({"ImageDescription", all.end().text()});
  }
}

}  // namespace

std::uint8_t encode_gamma2_8bit(float linear) {
  const float v = std::sqrt(std::clamp(std::isnan(linear) ? 0.0f : linear, 0.0f, 1.0f));
  return static_cast<std::uint8_t>(std::lround(v * 255.0f));
}

void write_image(const std::string& path, const Film& film, const Metadata& metadata,
                 const std::vector<ExtraChannel>& extra, const FramePlacement& placement) {
  const ImageFormat* image = image_format(path);
  if (!image || (!extra.empty() && !image->extra_channels)) {
    throw std::invalid_argument("cannot write '" + path + "': not a format for this image");
  }
  const bool linear_float = image->linear_float;
  const int channels = 3 + int(extra.size());
  ImageHeader header;
  header.width = header.full_width = film.width();
  header.height = header.full_height = film.height();
  if (!placement.whole() && image->data_window) {
    header.x = placement.x, header.y = placement.y;
    header.full_width = placement.frame_width, header.full_height = placement.frame_height;
  }
  header.channel_names = {"R", "G", "B"};
  for (const ExtraChannel& e : extra) header.channel_names.push_back(e.name);
  header.channel_types.assign(std::size_t(channels),
                              linear_float ? PixelType::Float : PixelType::UInt8);
  add_metadata(header, metadata, linear_float, image->provenance);
  if (!linear_float) header.attributes.push_back({"oiio:ColorSpace", std::string("Gamma2.0")});

  // The pixels [first, end), interleaved as the header says: linear floats with the extra
  // channels, or gamma-encoded bytes.
  std::vector<float> floats;
  std::vector<std::uint8_t> bytes;
  const auto interleave = [&](std::size_t first, std::size_t end) -> const void* {
    floats.clear(), bytes.clear();
    for (std::size_t p = first; p < end; ++p) {
      const Color& c = film.pixels()[p];
      if (linear_float) {
        floats.insert(floats.end(), {c.x, c.y, c.z});
        for (const ExtraChannel& e : extra) floats.push_back(e.values[p]);
      } else {
        bytes.insert(bytes.end(),
                     {encode_gamma2_8bit(c.x), encode_gamma2_8bit(c.y), encode_gamma2_8bit(c.z)});
      }
    }
    return linear_float ? static_cast<const void*>(floats.data()) : bytes.data();
  };
  const std::size_t width = std::size_t(film.width());
  std::vector<unsigned char> encoded;
  std::string reason;
  const bool ok =
      image->own_encoder
          ? encode_png(header,
                       static_cast<const std::uint8_t*>(interleave(0, film.pixels().size())),
                       encoded, reason)
          : image_backend().encode(
                path, header,
                [&](int y_begin, int y_end) {
                  return interleave(std::size_t(y_begin) * width, std::size_t(y_end) * width);
                },
                encoded, reason);
  if (!ok) throw std::runtime_error("cannot write '" + path + "': " + reason);
  write_bytes_atomically(path, encoded);
}

}  // namespace rtiow
