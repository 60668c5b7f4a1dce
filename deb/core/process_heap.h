// Internal: not part of the public API.
// The heap of a short-lived deb process on transparent huge pages.
//
// A run of a small budget touches about 2 MB of fresh heap (the unit
// database, the YAML tree, the result files' text). Each first touch of a
// 4 KiB page is a page fault, and on a virtual machine a fault costs tens of
// microseconds: 560 of them were most of a 29 ms thesis-budget run. Backed by
// 2 MiB pages, the same memory takes a handful of faults.
#pragma once

namespace deb {

// Asks the C library to grow the heap in steps of `step_mib` MiB and to keep
// what it frees, and asks the kernel to back the heap's 2 MiB-aligned part
// with transparent huge pages (Linux, where THP is "madvise" or "always").
// Costs resident memory in whole 2 MiB pages (a few MiB), saves page faults.
// Call once, first thing in main(), before threads start. Where the C
// library or kernel lacks a part, or another allocator replaces the C
// library's (AddressSanitizer), nothing is done; nothing fails. Returns true
// when the heap was advised.
bool UseHugePagesForHeap(int step_mib = 8);

}  // namespace deb
