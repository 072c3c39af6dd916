// rtiow's own PNG encoder writes what the image library wrote: the same 8-bit pixels (the
// book's gamma 2), its gamma and its metadata, readable by the image library; and a failure
// inside libpng comes back as a reason, not as a crash or an exit.

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "core/io/image_backend.h"
#include "core/io/image_file.h"
#include "core/io/image_output.h"
#include "core/io/png_encoder.h"
#include "core/version.h"

namespace rtiow {
namespace {

namespace fs = std::filesystem;

Film gradient(int width, int height) {
  Film film(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      // Below 0, above 1 and NaN too: the encoding clamps them as the book does.
      film.at(x, y) = Color(float(x) / float(width - 1) * 1.2f - 0.1f, float(y) / float(height),
                            (x + y) % 7 == 0 ? std::numeric_limits<float>::quiet_NaN() : 0.25f);
    }
  }
  return film;
}

std::vector<std::uint8_t> read_bytes(const std::string& path, ImageHeader& header) {
  std::string reason;
  auto in = image_backend().open(path, "png", reason);
  EXPECT_TRUE(in) << reason;
  if (!in) return {};
  header = in->header();
  std::vector<std::uint8_t> pixels(std::size_t(header.width) * std::size_t(header.height) *
                                   header.channel_names.size());
  EXPECT_TRUE(in->read_pixels(PixelType::UInt8, pixels.data(), reason)) << reason;
  return pixels;
}

TEST(PngEncoder, WritesTheBooksEightBitsAndTheMetadataAsTheImageLibraryReadsThem) {
  const fs::path path = fs::path(RTIOW_TEST_OUTPUT_DIR) / "png_encoder.png";
  const Film film = gradient(37, 23);  // odd sizes: no row padding assumed
  write_image(path.string(), film, {{"seed", std::int64_t(7)}, {"scene", std::string("cover")}});
  ImageHeader header;
  const std::vector<std::uint8_t> pixels = read_bytes(path.string(), header);
  ASSERT_EQ(header.width, 37);
  ASSERT_EQ(header.height, 23);
  ASSERT_EQ(header.channel_names.size(), 3u);
  for (std::size_t p = 0; p < film.pixels().size(); ++p) {
    const Color& c = film.pixels()[p];
    ASSERT_EQ(pixels[3 * p + 0], encode_gamma2_8bit(c.x)) << p;
    ASSERT_EQ(pixels[3 * p + 1], encode_gamma2_8bit(c.y)) << p;
    ASSERT_EQ(pixels[3 * p + 2], encode_gamma2_8bit(c.z)) << p;
  }
  EXPECT_EQ(header.string_attribute("rtiow:seed"), "7");
  EXPECT_EQ(header.string_attribute("rtiow:scene"), "cover");
  EXPECT_EQ(header.string_attribute("Software"), std::string("rtiow ") + version());
  bool gamma_two = false;  // from the gAMA chunk, as the image library's own PNGs carry it
  for (const ImageAttribute& a : header.attributes) {
    if (a.name == "oiio:Gamma") gamma_two = std::get<float>(a.value) == 2.0f;
  }
  EXPECT_TRUE(gamma_two);
}

TEST(PngEncoder, ALibpngErrorIsAReason) {
  ImageHeader header;
  header.width = 0, header.height = 4;  // libpng refuses an empty image
  std::vector<unsigned char> bytes;
  std::string reason;
  const std::uint8_t pixel[3] = {};
  EXPECT_FALSE(encode_png(header, pixel, bytes, reason));
  EXPECT_NE(reason.find("PNG encoder: "), std::string::npos) << reason;
  EXPECT_GT(reason.size(), std::string("PNG encoder: ").size()) << reason;
}

}  // namespace
}  // namespace rtiow
