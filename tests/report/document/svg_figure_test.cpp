#include "deb/report/document/svg_figure.h"

#include <cairo-pdf.h>
#include <cairo.h>
#include <doctest/doctest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
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

TEST_CASE("an opaque text box is drawn as vectors, a white halo round the glyphs, not a rasterised filter") {
  // gnuplot's SVG: a text box is a filter on a first copy of the text; librsvg
  // rasterised it and the PDF showed a grey chip. The page holds no image.
  const test::ScratchDir dir("svg_textbox");
  const std::string svg = dir.Write(
      "t.svg",
      "<svg xmlns='http://www.w3.org/2000/svg' width='200' height='100' viewBox='0 0 200 100'>\n<defs>"
      "<filter id='textbox' filterUnits='objectBoundingBox' x='0' y='0' height='1' width='1'>"
      "<feFlood flood-color='white' flood-opacity='1' result='bgnd'/>"
      "<feComposite in='SourceGraphic' in2='bgnd' operator='atop'/></filter></defs>\n"
      "<rect x='0' y='0' width='200' height='100' fill='#2166ac'/>\n"
      "<g transform='translate(40,60)' fill='rgb(0,0,0)' font-size='20' style='filter:url(#textbox)'><text>1.00</text></g>\n"
      "<g transform='translate(40,60)' fill='rgb(0,0,0)' font-size='20'><text>1.00</text></g>\n</svg>\n");
  const std::string pdf = dir.Path("t.pdf");
  {
    const SvgFigure figure(svg);
    cairo_surface_t* surface = cairo_pdf_surface_create(pdf.c_str(), 200, 100);
    cairo_t* cr = cairo_create(surface);
    figure.Draw(cr, 0, 0, 200, 100);
    cairo_destroy(cr);
    cairo_surface_destroy(surface);
  }
  std::ifstream in(pdf, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  CHECK(bytes.str().find("/Subtype /Image") == std::string::npos);
  // In a PNG, the text still stands on white: just left of the "1" the halo covers the blue.
  const std::string png = dir.Path("t.png");
  RasteriseSvg(svg, png, 200, 100);
  cairo_surface_t* s = cairo_image_surface_create_from_png(png.c_str());
  REQUIRE(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS);
  CHECK(Pixel(s, 10, 10) == 0x2166acu);  // the background, away from the text
  cairo_surface_destroy(s);
}

}  // namespace deb::report
