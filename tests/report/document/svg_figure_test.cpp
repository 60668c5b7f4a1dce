#include "deb/report/document/svg_figure.h"

#include <cairo.h>
#include <doctest/doctest.h>

#include <cstdint>
#include <filesystem>
#include <string>

#include "deb/core/error.h"
#include "tests/support/scratch_dir.h"

namespace deb::report {
namespace {

// The pixel (x, y) of a PNG as 0xRRGGBB.
std::uint32_t Pixel(cairo_surface_t* s, int x, int y) {
  const unsigned char* data = cairo_image_surface_get_data(s);
  return *reinterpret_cast<const std::uint32_t*>(data + y * cairo_image_surface_get_stride(s) + 4 * x) & 0xffffffu;
}

}  // namespace

TEST_CASE("an SVG is rasterised onto white at the size asked, scaled to it") {
  const test::ScratchDir dir("svg_figure");
  // 100 x 50 user units, the top right quarter red, a blue square at the
  // lower left; nothing else drawn (the background stays white).
  const std::string svg = dir.Write("f.svg",
                                    "<svg xmlns='http://www.w3.org/2000/svg' width='100' height='50' "
                                    "viewBox='0 0 100 50'>\n"
                                    "<rect x='50' y='0' width='50' height='25' fill='#ff0000'/>\n"
                                    "<rect x='10' y='30' width='10' height='10' fill='#0000ff'/>\n</svg>\n");
  const SvgFigure figure(svg);
  CHECK(figure.width() == 100.0);
  CHECK(figure.height() == 50.0);
  const std::string png = dir.Path("f.png");
  RasteriseSvg(svg, png, 400, 200);  // 4 times
  cairo_surface_t* s = cairo_image_surface_create_from_png(png.c_str());
  REQUIRE(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS);
  CHECK(cairo_image_surface_get_width(s) == 400);
  CHECK(cairo_image_surface_get_height(s) == 200);
  CHECK(Pixel(s, 300, 50) == 0xff0000u);   // inside the red quarter
  CHECK(Pixel(s, 201, 1) == 0xff0000u);    // its corner at (200, 0), pixel-aligned
  CHECK(Pixel(s, 198, 1) == 0xffffffu);    // just left of it
  CHECK(Pixel(s, 300, 101) == 0xffffffu);  // just below it
  CHECK(Pixel(s, 60, 140) == 0x0000ffu);   // the blue square, 40..80 x 120..160
  CHECK(Pixel(s, 85, 140) == 0xffffffu);
  CHECK(Pixel(s, 10, 190) == 0xffffffu);
  cairo_surface_destroy(s);
  // Rasterised again at another size, the same thread's canvas is remade.
  RasteriseSvg(svg, png, 100, 50);
  s = cairo_image_surface_create_from_png(png.c_str());
  REQUIRE(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS);
  CHECK(cairo_image_surface_get_width(s) == 100);
  CHECK(Pixel(s, 75, 12) == 0xff0000u);
  CHECK(Pixel(s, 25, 12) == 0xffffffu);
  cairo_surface_destroy(s);
}

TEST_CASE("an SVG that cannot be read or has no size is an error naming it, and no PNG is written") {
  const test::ScratchDir dir("svg_figure_errors");
  const std::string png = dir.Path("f.png");
  CHECK_THROWS_WITH_AS(RasteriseSvg(dir.Path("missing.svg"), png, 10, 10), doctest::Contains("cannot read figure"),
                       WriteError);
  const std::string garbage = dir.Write("g.svg", "this is not < an svg");
  CHECK_THROWS_WITH_AS(RasteriseSvg(garbage, png, 10, 10), doctest::Contains(("cannot read figure " + garbage).c_str()),
                       WriteError);
  const std::string sizeless = dir.Write("s.svg", "<svg xmlns='http://www.w3.org/2000/svg' width='0' height='0'/>");
  CHECK_THROWS_WITH_AS(RasteriseSvg(sizeless, png, 10, 10), doctest::Contains("has no size"), WriteError);
  CHECK_THROWS_WITH_AS(RasteriseSvg(sizeless, png, 0, 10), doctest::Contains("0 x 10 pixels"), InputError);
  CHECK_FALSE(std::filesystem::exists(png));
}

}  // namespace deb::report
