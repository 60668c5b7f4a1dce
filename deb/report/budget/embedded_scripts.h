// Internal: not part of the public API.
// The scripts index.html carries, built into deb (deb/CMakeLists.txt) so that
// every page is one file and every machine writes the same page:
// - dygraphs 2.x (MIT licence; its licence comment is part of the text), the
//   JavaScript plotting library, with its synchronizer extension and style
//   sheet, read from Debian's libjs-dygraphs without source-map comments;
// - deb/report/budget/index_figures.js, the page's own code that draws the figures.
#pragma once

namespace deb::report {

const char* DygraphsJs();
const char* DygraphsCss();
const char* IndexFiguresJs();

}  // namespace deb::report
