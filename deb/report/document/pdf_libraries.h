// Internal: not part of the public API.
// cairo, pango and librsvg for pdf_document.cpp, which alone includes this.
// They are not linked: they are loaded when the first document is written.
// Linked, they and what they need (46 shared libraries, GIO and gdk-pixbuf
// among them) cost 4 ms of every start of deb, a report or not. Only the
// functions listed here are used; each is a pointer in deb::report named as
// the function, which it hides from code in that namespace, so that the
// code reads as if the libraries were linked.
#pragma once

#include <cairo-pdf.h>
#include <cairo.h>
#include <librsvg/rsvg.h>
#include <pango/pangocairo.h>

namespace deb::report {

#define DEB_PDF_FUNCTIONS(X)                                                                                \
  X(cairo_create) X(cairo_destroy) X(cairo_fill) X(cairo_line_to) X(cairo_move_to) X(cairo_pdf_surface_add_outline) \
  X(cairo_pdf_surface_create) X(cairo_pdf_surface_create_for_stream) X(cairo_pdf_surface_set_metadata)         \
  X(cairo_rectangle) X(cairo_restore) X(cairo_save) X(cairo_set_line_width) X(cairo_set_source_rgb)           \
  X(cairo_show_page) X(cairo_status_to_string) X(cairo_stroke) X(cairo_surface_destroy) X(cairo_surface_finish) \
  X(cairo_surface_status) X(cairo_tag_begin) X(cairo_tag_end) X(g_error_free) X(g_object_unref)              \
  X(pango_cairo_create_layout) X(pango_cairo_show_layout) X(pango_font_description_free)                      \
  X(pango_font_description_from_string) X(pango_font_description_set_absolute_size)                          \
  X(pango_font_description_set_style) X(pango_font_description_set_weight) X(pango_layout_get_size)          \
  X(pango_layout_set_font_description) X(pango_layout_set_text) X(pango_layout_set_width)                    \
  X(pango_layout_set_wrap) X(pango_layout_set_indent) X(pango_layout_set_tabs) X(pango_tab_array_new_with_positions) \
  X(pango_tab_array_free) X(pango_layout_get_pixel_extents) X(cairo_set_dash) X(cairo_set_line_cap)             \
  X(rsvg_handle_get_intrinsic_size_in_pixels) X(rsvg_handle_new_from_file)          \
  X(rsvg_handle_render_document)
#define DEB_PDF_POINTER(f) extern decltype(&::f) f;
DEB_PDF_FUNCTIONS(DEB_PDF_POINTER)
#undef DEB_PDF_POINTER

// Loads the libraries once; every pointer above is set after it returns.
// @throws WriteError naming the library or function that cannot be loaded.
void RequirePdfLibraries();

}  // namespace deb::report
