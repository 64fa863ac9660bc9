// SPDX-License-Identifier: LGPL-2.1-or-later
// How the process's heap treats the large blocks a solve allocates and frees.
//
// Why: glibc hands blocks of a few MiB back to the kernel when they are freed (mmap'd blocks, and
// the heap's top beyond its trim threshold), so the next solve's blocks of the same sizes fault
// in every page again. On the 2-core virtual machine measured a page fault is expensive: a
// 19 x 19 sheet through 10 curves (13 300 samples, benchmark 2) took 33 ms, 20 of them in a
// stage that mostly faulted its memory in; with the freed blocks kept, 14 ms (that stage 1.5 ms).
// Through 5 curves: 12 ms, now 6.
#pragma once

namespace varsurf {

// Keeps freed heap memory in the process for reuse (up to a bound) instead of returning it to
// the kernel after each solve. Process-wide and idempotent; a no-op where the C library has no
// such setting. Called once when the Python module loads.
void keep_freed_heap();

}  // namespace varsurf
