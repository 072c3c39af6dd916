#include "core/io/image_channels.h"

#include <algorithm>

#include "core/io/image_backend.h"
#include "core/limits/error.h"
#include "core/limits/image_size.h"
#include "core/limits/input_limits.h"

namespace rtiow {

int ImageChannels::index(const std::string& name) const {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : int(it - names.begin());
}

std::vector<float> ImageChannels::plane(std::size_t channel) const {
  const std::size_t count = names.size();
  std::vector<float> out(std::size_t(width) * std::size_t(height));
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = values[p * count + channel];
  return out;
}

ImageChannels read_image_channels(const std::string& path, const std::string& name,
                                  std::size_t least_channels) {
  auto in = open_input_image(path, name, limits::kMaxPartFileBytes, "image");
  const ImageHeader& header = in->header();
  const std::size_t channels = header.channel_names.size();
  if (header.width < 1 || header.height < 1 || header.width > limits::kMaxImageSide ||
      header.height > limits::kMaxImageSide || channels < least_channels || channels > 64) {
    throw InvalidInput(name + ": " + std::to_string(header.width) + "x" +
                       std::to_string(header.height) + " with " + std::to_string(channels) +
                       " channels is not an image rtiow reads (R, G, B needed)");
  }
  try {  // the header decides what is allocated: the float values of every channel
    check_image_size(header.width, header.height, channels * sizeof(float));
  } catch (const InvalidInput& e) {
    throw InvalidInput(name + ": " + e.what());
  }
  ImageChannels image;
  image.width = header.width, image.height = header.height;
  image.names = header.channel_names;
  image.types = header.channel_types;
  image.values.resize(std::size_t(header.width) * std::size_t(header.height) * channels);
  std::string reason;
  if (!in->read_pixels(PixelType::Float, image.values.data(), reason)) {
    throw InvalidInput(name + ": cannot read its pixels: " + one_line(reason, 200));
  }
  return image;
}

}  // namespace rtiow
