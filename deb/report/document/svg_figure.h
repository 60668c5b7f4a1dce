// Internal: not part of the public API.
// A figure gnuplot drew as SVG, read by librsvg (used by this module only):
// placed as vectors on a page of report.pdf (pdf_document.cpp), or
// rasterised into a PNG. A report's PNGs are drawn this way, from gnuplot's
// SVG, rather than by gnuplot's PNG terminal: one drawing (gnuplot writes
// SVG in a fraction of the time), rasterised in deb's own threads and encoded
// with a fixed, fast PNG setting (png_image.h).
#pragma once

#include <string>

typedef struct _cairo cairo_t;
typedef struct _RsvgHandle RsvgHandle;

namespace deb::report {

class SvgFigure {
 public:
  // Parses `file`.
  // @throws WriteError naming the file if it cannot be read or parsed, or
  //   has no size.
  explicit SvgFigure(const std::string& file);
  ~SvgFigure();
  SvgFigure(const SvgFigure&) = delete;
  SvgFigure& operator=(const SvgFigure&) = delete;

  // The size gnuplot gave it (its terminal's size), in SVG user units.
  double width() const { return width_; }
  double height() const { return height_; }
  // Draws it scaled into the rectangle (x, y, w, h) of `cr`.
  // @throws WriteError naming the file if librsvg cannot draw it.
  void Draw(cairo_t* cr, double x, double y, double w, double h) const;

 private:
  std::string file_;
  RsvgHandle* handle_ = nullptr;
  double width_ = 0.0, height_ = 0.0;
};

// Rasterises the SVG file `svg_file` onto white, scaled to width_px x
// height_px, and writes it as the PNG `png_file` (png_image.h).
// @throws WriteError naming the file that cannot be read, drawn or written
//   (a PNG not completely written is removed).
void RasteriseSvg(const std::string& svg_file, const std::string& png_file, int width_px, int height_px);

}  // namespace deb::report
