#include "deb/report/document/svg_figure.h"

#include <cairo.h>
#include <librsvg/rsvg.h>

#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <string_view>

#include "deb/core/error.h"
#include "deb/report/document/png_image.h"

namespace deb::report {

SvgFigure::SvgFigure(const std::string& file) : file_(file) {
  // gnuplot writes a superscript's following text as a tspan that starts
  // with its space ("10</tspan><tspan>-3</tspan><tspan> of"), and librsvg
  // drops a tspan's leading space under SVG's default white-space
  // handling ("10^-3of"): the figure is parsed with xml:space="preserve"
  // on its root (gnuplot puts no other white space inside its texts).
  std::string svg_text;
  {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw WriteError("cannot read figure " + file);
    svg_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (const std::size_t root = svg_text.find("<svg"); root != std::string::npos)
    svg_text.insert(root + 4, " xml:space=\"preserve\"");
  // gnuplot sets an opaque text box ("set style textbox opaque") as an SVG
  // filter on a first copy of the text, drawn again plainly over it. librsvg
  // rasterises a filter, and on a PDF page the box came out as a grey chip
  // with a darker edge: the first copy becomes a white halo instead (a
  // stroke around the glyphs, vectors), which keeps lines and curves off the
  // text as the box did.
  constexpr std::string_view kBoxed = "style='filter:url(#textbox)'";
  constexpr std::string_view kHalo = "style='fill:white;stroke:white;stroke-width:4;stroke-linejoin:round'";
  for (std::size_t at = svg_text.find(kBoxed); at != std::string::npos; at = svg_text.find(kBoxed, at + kHalo.size()))
    svg_text.replace(at, kBoxed.size(), kHalo);
  GError* error = nullptr;
  handle_ = rsvg_handle_new_from_data(reinterpret_cast<const guint8*>(svg_text.data()), svg_text.size(), &error);
  if (!handle_) {
    const std::string why = error ? error->message : "unknown error";
    if (error) g_error_free(error);
    throw WriteError("cannot read figure " + file + ": " + why);
  }
  const gboolean has_size = rsvg_handle_get_intrinsic_size_in_pixels(handle_, &width_, &height_);
  if (!has_size || !(width_ > 0) || !(height_ > 0)) {
    g_object_unref(handle_);
    throw WriteError("cannot read figure " + file + ": the SVG has no size");
  }
}

SvgFigure::~SvgFigure() { g_object_unref(handle_); }

void SvgFigure::Draw(cairo_t* cr, double x, double y, double w, double h) const {
  cairo_save(cr);
  const RsvgRectangle viewport{x, y, w, h};
  GError* error = nullptr;
  const gboolean ok = rsvg_handle_render_document(handle_, cr, &viewport, &error);
  cairo_restore(cr);
  if (!ok) {
    const std::string why = error ? error->message : "unknown error";
    if (error) g_error_free(error);
    throw WriteError("cannot draw figure " + file_ + ": " + why);
  }
}

void RasteriseSvg(const std::string& svg_file, const std::string& png_file, int width_px, int height_px) {
  if (width_px <= 0 || height_px <= 0)
    throw InputError("cannot draw " + png_file + " at " + std::to_string(width_px) + " x " +
                     std::to_string(height_px) + " pixels");
  const SvgFigure svg(svg_file);
  struct SurfaceDeleter {
    void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
  };
  struct ContextDeleter {
    void operator()(cairo_t* c) const { cairo_destroy(c); }
  };
  // One canvas per thread, kept for the next figure of its size: a new one
  // of a few MB would be mapped and faulted in page by page each time.
  thread_local std::unique_ptr<cairo_surface_t, SurfaceDeleter> surface;
  if (!surface || cairo_image_surface_get_width(surface.get()) != width_px ||
      cairo_image_surface_get_height(surface.get()) != height_px) {
    surface.reset(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_px, height_px));
    if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) {
      const std::string why = cairo_status_to_string(cairo_surface_status(surface.get()));
      surface.reset();
      throw WriteError("cannot draw " + png_file + ": " + why);
    }
  }
  {
    const std::unique_ptr<cairo_t, ContextDeleter> cr(cairo_create(surface.get()));
    cairo_set_source_rgb(cr.get(), 1.0, 1.0, 1.0);
    cairo_paint(cr.get());
    svg.Draw(cr.get(), 0.0, 0.0, width_px, height_px);
    if (cairo_status(cr.get()) != CAIRO_STATUS_SUCCESS)
      throw WriteError("cannot draw " + png_file + ": " + cairo_status_to_string(cairo_status(cr.get())));
  }
  cairo_surface_flush(surface.get());
  WritePng(png_file, width_px, height_px, cairo_image_surface_get_data(surface.get()),
           cairo_image_surface_get_stride(surface.get()));
}

}  // namespace deb::report
