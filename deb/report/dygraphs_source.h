// Internal: not part of the public API.
// dygraphs 2.x (MIT licence; its licence comment is part of the text), the
// JavaScript plotting library index.html inlines, with its synchronizer
// extension and style sheet: read from Debian's libjs-dygraphs when deb is
// built (deb/CMakeLists.txt), without source-map comments.
#pragma once

namespace deb::report {

const char* DygraphsJs();
const char* DygraphsCss();

}  // namespace deb::report
