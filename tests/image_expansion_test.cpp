// What a file can hold (core/io/image_expansion.h): a PNM header read in its first bytes and
// its raw pixels all present; each format's bound at least what its best compression gives.

#include "core/io/image_expansion.h"

#include <gtest/gtest.h>

#include <string>

namespace rtiow {
namespace {

std::string with_pixels(const std::string& header, std::size_t bytes) {
  return header + std::string(bytes, '\x7f');
}

// The check sees the first kPnmHeaderBytes and the file's whole size.
std::string why(const std::string& file) {
  return why_not_a_pnm_image(file.substr(0, kPnmHeaderBytes), file.size());
}

TEST(PnmHeader, ReadsEveryKindWhoseHeaderAndPixelsAreThere) {
  EXPECT_EQ(why(with_pixels("P6\n4 3\n255\n", 4 * 3 * 3)), "");
  EXPECT_EQ(why(with_pixels("P6 4 3 65535\n", 4 * 3 * 3 * 2)), "");
  EXPECT_EQ(why(with_pixels("P5\n# a comment\n4 3\n# another\n255\n", 4 * 3)), "");
  EXPECT_EQ(why(with_pixels("P4\n9 2\n", 2 * 2)), "");  // a row of 9 bits takes 2 bytes
  EXPECT_EQ(why(with_pixels("PF\n4 3\n-1.0\n", 4 * 3 * 12)), "");
  EXPECT_EQ(why(with_pixels("Pf\n4 3\n-1.0\n", 4 * 3 * 4)), "");
  EXPECT_EQ(why("P3\n2 1\n255\n0 0 0 255 255 255\n"), "");
  EXPECT_EQ(why("P1\n3 1\n010"), "");
  EXPECT_EQ(why("P7\nWIDTH 2\nHEIGHT 2\nDEPTH 3\nMAXVAL 255\nTUPLTYPE RGB\nENDHDR\n" +
                std::string(12, '\0')),
            "");
}

TEST(PnmHeader, RefusesAHeaderNotThereAndPixelsNotThere) {
  // The image library read all of these looking for a header, or allocated the claimed size.
  EXPECT_NE(why("P6\n" + std::string(1 << 16, '\0')).find("holds no width"), std::string::npos);
  EXPECT_NE(why("P6\n" + std::string(1 << 16, ' ')).find("holds no width"), std::string::npos);
  EXPECT_NE(why("P6\n4 3").find("holds no width"), std::string::npos);       // ends in the header
  EXPECT_NE(why("P6\n4 3\n0\n").find("holds no width"), std::string::npos);  // maxval 0
  EXPECT_NE(why("P6\n4 3\n70000\n").find("holds no width"), std::string::npos);  // above 16 bits
  EXPECT_NE(why("P6\n9999999999999 3\n255\n").find("holds no width"), std::string::npos);
  EXPECT_NE(why("P6\n0 3\n255\n").find("outside 1 to"), std::string::npos);
  EXPECT_NE(why("P6\n2000000 3\n255\n").find("outside 1 to"), std::string::npos);
  const std::string short_of = why(with_pixels("P6\n5000 5000\n255\n", 100000));
  EXPECT_NE(short_of.find("take at least 75000000 bytes, but the file holds 100000"),
            std::string::npos)
      << short_of;
  EXPECT_NE(why(with_pixels("P6 4 3 65535\n", 4 * 3 * 3)).find("but the file holds"),
            std::string::npos);  // 16-bit samples take two bytes
  EXPECT_NE(why("P3\n100 100\n255\n0 0 0\n").find("but the file holds"), std::string::npos);
  EXPECT_NE(why("P7\nWIDTH 2\n" + std::string(5000, '\0')).find("no ENDHDR"), std::string::npos);
}

// Each bound at least the format's best ratio: deflate's 1032 for PNG and EXR's zip, and above
// what constant 4000x4000 images measured (docs in image_expansion.h); raw data's bound small.
TEST(ImageExpansion, EachFormatsBoundCoversItsBestCompression) {
  EXPECT_GE(max_expansion("png", ""), 1032u);
  EXPECT_LT(max_expansion("png", ""), 2048u);  // a 200 KB PNG cannot hold 10000x10000
  EXPECT_GE(max_expansion("openexr", "zip"), 1032u * 4 / 3);
  EXPECT_GE(max_expansion("openexr", "dwaa:45"), 3661u);
  EXPECT_GE(max_expansion("openexr", "piz"), 404u);
  EXPECT_GE(max_expansion("openexr", "rle"), 64u);
  EXPECT_LE(max_expansion("openexr", "none"), 2u);
  EXPECT_GE(max_expansion("tiff", ""), 1032u);
  EXPECT_GE(max_expansion("jpeg", ""), 191u);
  EXPECT_LE(max_expansion("pnm", ""), 8u);
  EXPECT_GE(max_expansion("something new", ""), max_expansion("openexr", "dwaa"));
}

}  // namespace
}  // namespace rtiow
