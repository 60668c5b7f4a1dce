#include "deb/report/document/png_image.h"

#include <cairo.h>
#include <doctest/doctest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "deb/core/error.h"
#include "tests/support/scratch_dir.h"

namespace deb::report {
namespace {

std::string Bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::uint32_t Big32(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(b[at + i]);
  return v;
}

}  // namespace

TEST_CASE("a PNG holds the pixels it was given, exactly, and the same pixels give the same bytes") {
  const test::ScratchDir dir("png_image");
  // 3 x 2 pixels, 0x??RRGGBB, rows padded to a stride of 16 bytes; the top
  // byte is ignored.
  const std::vector<std::uint32_t> colours = {0x00ff0000u, 0xff00ff00u, 0x000000ffu,
                                              0x00123456u, 0x00ffffffu, 0x00000000u};
  std::vector<std::uint8_t> pixels(2 * 16, 0xee);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      *reinterpret_cast<std::uint32_t*>(&pixels[static_cast<std::size_t>(16 * y + 4 * x)]) = colours[3 * y + x];
  const std::string a = dir.Path("a.png"), b = dir.Path("b.png");
  WritePng(a, 3, 2, pixels.data(), 16);
  WritePng(b, 3, 2, pixels.data(), 16);
  const std::string bytes = Bytes(a);
  CHECK(bytes == Bytes(b));
  REQUIRE(bytes.size() > 24);
  CHECK(bytes.substr(1, 3) == "PNG");
  CHECK(bytes.substr(12, 4) == "IHDR");
  CHECK(Big32(bytes, 16) == 3);  // width
  CHECK(Big32(bytes, 20) == 2);  // height
  CHECK(bytes.find("tIME") == std::string::npos);

  // Read back by cairo's own PNG reader.
  cairo_surface_t* s = cairo_image_surface_create_from_png(a.c_str());
  REQUIRE(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS);
  CHECK(cairo_image_surface_get_width(s) == 3);
  CHECK(cairo_image_surface_get_height(s) == 2);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      CAPTURE(x);
      CAPTURE(y);
      const std::uint32_t got = *reinterpret_cast<const std::uint32_t*>(data + y * stride + 4 * x);
      CHECK((got & 0xffffffu) == (colours[3 * y + x] & 0xffffffu));
    }
  cairo_surface_destroy(s);
}

TEST_CASE("a PNG that cannot be written is an error naming the file, and leaves no file") {
  const test::ScratchDir dir("png_image_errors");
  std::vector<std::uint8_t> pixels(16, 0);
  const std::string missing = dir.Path("no/such/dir/a.png");
  CHECK_THROWS_WITH_AS(WritePng(missing, 2, 2, pixels.data(), 8), doctest::Contains(("cannot write " + missing).c_str()),
                       WriteError);
  CHECK_FALSE(std::filesystem::exists(missing));
  CHECK_THROWS_WITH_AS(WritePng(dir.Path("z.png"), 0, 2, pixels.data(), 8), doctest::Contains("0 x 2 pixels"),
                       InputError);
  CHECK_THROWS_WITH_AS(WritePng(dir.Path("z.png"), 4, 2, pixels.data(), 8), doctest::Contains("stride 8"),
                       InputError);
  CHECK_FALSE(std::filesystem::exists(dir.Path("z.png")));
}

}  // namespace deb::report
