#include "deb/report/document/png_image.h"

#include <png.h>

#include <string>
#include <vector>

#include "deb/core/error.h"
#include "deb/core/output_dir.h"

namespace deb::report {
namespace {

// libpng reports errors by longjmp: the encoder runs in a function that
// holds no object with a destructor between setjmp and its end, and says
// only whether it succeeded.
struct Encoding {
  std::string* bytes = nullptr;
  bool failed_to_grow = false;
};

void Append(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<Encoding*>(png_get_io_ptr(png));
  try {
    out->bytes->append(reinterpret_cast<const char*>(data), length);
  } catch (...) {
    out->failed_to_grow = true;
    png_error(png, "out of memory");
  }
}

void NoFlush(png_structp) {}

void Quiet(png_structp, png_const_charp) {}

bool Encode(Encoding* out, int width, int height, const std::uint8_t* pixels, int stride, png_bytep row) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, Quiet);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, out, Append, NoFlush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, 6);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
  png_write_info(png, info);
  for (int y = 0; y < height; ++y) {
    const auto* px = reinterpret_cast<const std::uint32_t*>(pixels + static_cast<std::size_t>(y) * stride);
    for (int x = 0; x < width; ++x) {
      row[3 * x] = static_cast<png_byte>((px[x] >> 16) & 0xffu);
      row[3 * x + 1] = static_cast<png_byte>((px[x] >> 8) & 0xffu);
      row[3 * x + 2] = static_cast<png_byte>(px[x] & 0xffu);
    }
    png_write_row(png, row);
  }
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

void WritePng(const std::string& path, int width_px, int height_px, const std::uint8_t* pixels, int stride) {
  if (width_px <= 0 || height_px <= 0 || stride < 4 * width_px)
    throw InputError("cannot write " + path + ": an image of " + std::to_string(width_px) + " x " +
                     std::to_string(height_px) + " pixels (stride " + std::to_string(stride) + ")");
  std::string bytes;
  bytes.reserve(static_cast<std::size_t>(width_px) * height_px / 4);
  std::vector<png_byte> row(3 * static_cast<std::size_t>(width_px));
  Encoding out{&bytes};
  if (!Encode(&out, width_px, height_px, pixels, stride, row.data()))
    throw WriteError("cannot write " + path + ": " + (out.failed_to_grow ? "out of memory" : "PNG encoding failed"));
  WriteTextFile(path, bytes);
}

}  // namespace deb::report
