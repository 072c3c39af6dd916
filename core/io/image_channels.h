#pragma once
// An image file's channels as float values, whatever they are (R, G, B, the statistics and
// pass channels of an EXR, the denoiser's): what `rtiow diff` compares and what a script reads
// back from a file rtiow wrote. Opened as every input is (core/io/image_backend.h: checked,
// bounded by its bytes and rtiow's image limits before a pixel is allocated).

#include <cstddef>
#include <string>
#include <vector>

#include "core/io/image_file.h"

namespace rtiow {

struct ImageChannels {
  int width = 0, height = 0;
  std::vector<std::string> names;
  std::vector<PixelType> types;  // how each channel is stored in the file
  std::vector<float> values;     // interleaved: width * height * names.size(), row major

  // The index of the channel called `name`, or -1.
  int index(const std::string& name) const;
  // One channel's values, width * height, row major.
  std::vector<float> plane(std::size_t channel) const;
};

// Throws InvalidInput "<name>: <reason>" in one line when the file cannot be read as an image
// of at least `least_channels` channels (at most 64).
ImageChannels read_image_channels(const std::string& path, const std::string& name,
                                  std::size_t least_channels);

}  // namespace rtiow
