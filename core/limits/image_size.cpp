#include "core/limits/image_size.h"

#include <unistd.h>

#include <string>

#include "core/limits/error.h"
#include "core/limits/input_limits.h"

namespace rtiow {

void check_image_size(int width, int height, std::uint64_t bytes_per_pixel) {
  if (width <= 0) throw InvalidInput("width must be > 0, got " + std::to_string(width));
  if (height <= 0) throw InvalidInput("height must be > 0, got " + std::to_string(height));
  const std::string size = "image " + std::to_string(width) + "x" + std::to_string(height);
  if (width > limits::kMaxImageSide || height > limits::kMaxImageSide) {
    throw InvalidInput(size + ": each side must be at most " +
                       std::to_string(limits::kMaxImageSide));
  }
  const std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);
  if (pixels > limits::kMaxPixels) throw InvalidInput(size + " has more than 2^31 pixels");
  const std::uint64_t needed = pixels * bytes_per_pixel;
  const std::uint64_t available = physical_memory_bytes();
  if (needed > available / 2) {
    throw InvalidInput(size + " needs " + std::to_string(needed >> 20) +
                       " MiB, more than half of this machine's " + std::to_string(available >> 20) +
                       " MiB");
  }
}

std::uint64_t physical_memory_bytes() {
  return std::uint64_t(sysconf(_SC_PHYS_PAGES)) * std::uint64_t(sysconf(_SC_PAGESIZE));
}

}  // namespace rtiow
