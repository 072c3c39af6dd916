#pragma once
// Writing a film: PNG by rtiow's own encoder (core/io/png_encoder.h), every other format through
// the image library (core/io/image_backend.h). The format follows the file extension (the list is
// in core/io/output_path.h): float formats (.exr, .hdr) get linear values, 8-bit formats (.png,
// .jpg, .ppm, .tif, ...) the book's gamma 2. Every format is encoded in memory and its bytes
// written by core/io/atomic_file.h: a temporary rtiow creates exclusively, renamed over the target
// only when complete, so a failed write never leaves a truncated image or touches another file.

#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/film/film.h"

namespace rtiow {

// Metadata stored with the image: typed where the format allows, as strings otherwise.
using MetadataValue = std::variant<std::int64_t, double, std::string>;
using Metadata = std::vector<std::pair<std::string, MetadataValue>>;

// A count or a seed as metadata: a whole number, or its digits where it is past what an int64
// holds (a seed's 64 bits), so that it reads back as itself.
inline MetadataValue whole_metadata(std::uint64_t value) {
  if (value > std::uint64_t(std::numeric_limits<std::int64_t>::max())) return std::to_string(value);
  return std::int64_t(value);
}

// Every metadata key is stored in a file with this prefix (the keys:
// core/render/render_metadata.h).
inline constexpr const char* kMetadataPrefix = "rtiow:";

// A named per-pixel value written after R, G, B (float formats only), e.g. "spp".
struct ExtraChannel {
  std::string name;
  std::vector<float> values;  // one per pixel, row major
};

// Throws std::runtime_error with the encoder's or the system's reason on failure; the target is
// then untouched.
// The format must be one of image_format()'s, and extra channels need one that holds them
// (throws std::invalid_argument otherwise): check_image_output() refuses both before work.
// A film that is a crop of a larger frame (`placement`) keeps its place in a format with a
// data window (EXR: data window at the crop, display window the frame); the others hold the
// film alone.
void write_image(const std::string& path, const Film& film, const Metadata& metadata = {},
                 const std::vector<ExtraChannel>& extra = {}, const FramePlacement& placement = {});

// The book's gamma 2 and 8-bit quantisation, applied to one linear value.
std::uint8_t encode_gamma2_8bit(float linear);

}  // namespace rtiow
