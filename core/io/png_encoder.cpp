#include "core/io/png_encoder.h"

#include <png.h>

#include <csetjmp>
#include <cstring>
#include <new>
#include <variant>

namespace rtiow {
namespace {

// Where libpng's messages and output go during one encode.
struct Encoding {
  std::vector<unsigned char>* bytes;
  char error[200] = {};
};

void append_bytes(png_structp png, png_bytep data, png_size_t length) {
  auto* e = static_cast<Encoding*>(png_get_io_ptr(png));
  try {
    e->bytes->insert(e->bytes->end(), data, data + length);
  } catch (const std::bad_alloc&) {
    // No C++ exception may cross libpng's C frames: its own error path unwinds them.
    png_error(png, "out of memory for the encoded image");
  }
}

void no_flush(png_structp) {}

// libpng's errors do not return: the message is kept and control goes back to encode_png.
[[noreturn]] void on_error(png_structp png, png_const_charp message) {
  auto* e = static_cast<Encoding*>(png_get_error_ptr(png));
  std::strncpy(e->error, message ? message : "libpng failed", sizeof e->error - 1);
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}  // nothing rtiow writes warns

// The libpng calls, in a function of their own that holds nothing a longjmp could skip or
// clobber (libpng's errors return here through setjmp). False when libpng failed.
bool write_png(png_structp png, png_infop info, Encoding& encoding, int width, int height,
               png_textp texts, int text_count, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_write_fn(png, &encoding, append_bytes, no_flush);
  // zlib level 3, not the default 6: the encoding is serial at the end of every render, and a
  // rendered image's noise barely compresses: 3x faster for 6-9% more bytes (the cover at
  // 400x225: 17.0 -> 6.1 ms, 121 -> 128 KB; docs/performance.md).
  png_set_compression_level(png, 3);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_gAMA_fixed(png, info, 50000);  // the file's gamma: 1 / 2.0
  if (text_count > 0) png_set_text(png, info, texts, text_count);
  png_set_rows(png, info, rows);
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  return true;
}

}  // namespace

bool encode_png(const ImageHeader& header, const std::uint8_t* rgb,
                std::vector<unsigned char>& bytes, std::string& reason) {
  std::vector<png_text> texts;
  for (const ImageAttribute& a : header.attributes) {
    if (const auto* s = std::get_if<std::string>(&a.value)) {
      png_text t{};
      t.compression = PNG_TEXT_COMPRESSION_NONE;
      t.key = const_cast<char*>(a.name.c_str());
      t.text = const_cast<char*>(s->c_str());
      t.text_length = s->size();
      texts.push_back(t);
    }
  }
  std::vector<png_bytep> rows(std::size_t(header.height));
  const std::size_t stride = std::size_t(header.width) * 3;
  for (std::size_t y = 0; y < rows.size(); ++y) rows[y] = const_cast<png_bytep>(rgb + y * stride);
  Encoding encoding{&bytes};
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &encoding, on_error, on_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    reason = "out of memory for the PNG encoder";
    return false;
  }
  const bool written = write_png(png, info, encoding, header.width, header.height, texts.data(),
                                 int(texts.size()), rows.data());
  png_destroy_write_struct(&png, &info);
  if (!written) reason = std::string("PNG encoder: ") + encoding.error;
  return written;
}

}  // namespace rtiow
