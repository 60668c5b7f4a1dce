// Internal: not part of the public API.
// The C library's heap, set for deb's large, short-lived blocks.
//
// A budget's evaluation allocates and frees blocks of megabytes many times
// (a path's responses over a chunk of the grid, a modal model's shapes).
// By default glibc serves a block above 128 KiB to 32 MiB (its adaptive
// threshold) from a fresh mapping and returns it on free, so every new
// block is faulted in again page by page. Measured on a 1000-mode modal
// budget (deb run --no-plots -j1): 26 000 page faults and 0.89 s of CPU by
// default, 5 100 and 0.63 s with blocks to 16 MiB kept; on a dense
// 1000-mode model (2000 states, whose n x n matrices are 30.5 MiB each)
// 312 000 page faults with 16 MiB, 171 000 with 32 MiB (docs/developer.md).
#pragma once

namespace deb {

// Serves blocks up to 32 MiB (glibc's largest threshold on 64-bit systems)
// from the heap, keeps up to 128 MiB of freed heap instead of giving it
// back, and grows the heap in 8 MiB steps.
// Linux with glibc only (elsewhere, and under AddressSanitizer's allocator,
// nothing is done). Call once, first thing in main(), before threads start.
// Returns true when the settings were taken.
bool KeepHeapForLargeBlocks();

}  // namespace deb
