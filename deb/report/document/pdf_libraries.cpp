#include "deb/report/document/pdf_libraries.h"

#include <string>
#include <vector>

#include "deb/core/error.h"
#include "deb/core/shared_library.h"

namespace deb::report {

#define DEB_PDF_POINTER(f) decltype(&::f) f = nullptr;
DEB_PDF_FUNCTIONS(DEB_PDF_POINTER)
#undef DEB_PDF_POINTER

namespace {

// The libraries by soname (stable for over a decade), each with what it needs.
constexpr const char* kPdfLibraries[] = {"libglib-2.0.so.0", "libgobject-2.0.so.0", "libcairo.so.2",
                                         "libpango-1.0.so.0", "libpangocairo-1.0.so.0", "librsvg-2.so.2"};

// Why the libraries cannot be used; "" once every function is found.
std::string LoadPdfLibraries() {
  // Never unloaded (SharedLibrary): GLib keeps process-wide state until exit.
  std::vector<SharedLibrary> libraries;
  for (const char* soname : kPdfLibraries) {
    libraries.emplace_back(soname);
    if (!libraries.back().loaded()) return libraries.back().failure();
  }
  // Each function from the first library that has it.
  const auto resolve = [&](const char* name, auto& f) {
    for (SharedLibrary& library : libraries)
      if (library.Has(name)) return library.Resolve(name, f);
    return false;
  };
  std::string missing;
#define DEB_PDF_RESOLVE(f) \
  if (!resolve(#f, f)) missing += std::string(missing.empty() ? "" : ", ") + #f;
  DEB_PDF_FUNCTIONS(DEB_PDF_RESOLVE)
#undef DEB_PDF_RESOLVE
  return missing.empty() ? "" : "the libraries have no function " + missing;
}

}  // namespace

void RequirePdfLibraries() {
  static const std::string failure = LoadPdfLibraries();
  if (!failure.empty())
    throw WriteError("cannot typeset report.pdf: cairo, pango and librsvg cannot be loaded (" + failure +
                     "); install them (Debian: libcairo2 libpango-1.0-0 libpangocairo-1.0-0 librsvg2-2) or "
                     "leave pdf out of --format");
}

}  // namespace deb::report
