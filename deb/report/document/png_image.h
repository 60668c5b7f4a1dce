// Internal: not part of the public API.
// Writes an RGB image as a PNG file with libpng (used by this module only).
// The encoding is fixed, so the same pixels always give the same bytes:
// no time stamp or text chunks, no filter (a report's plots are mostly flat
// colour, which the per-row filters only make larger), zlib level 6.
#pragma once

#include <cstdint>
#include <string>

namespace deb::report {

// `pixels`: height_px rows of `stride` bytes, each row width_px pixels of 32
// bits in native byte order, 0x??RRGGBB (cairo's RGB24 and ARGB32 layout;
// the top byte is ignored).
// @throws WriteError naming `path` if the image cannot be encoded or written
//   (the file is then removed); InputError if a size is not positive.
void WritePng(const std::string& path, int width_px, int height_px, const std::uint8_t* pixels, int stride);

}  // namespace deb::report
