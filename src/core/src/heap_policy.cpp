// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/heap_policy.hpp"

#include <cstdlib>  // defines __GLIBC__ on glibc; the test below must not depend on other headers

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace varsurf {

void keep_freed_heap() {
#if defined(__GLIBC__)
  // Blocks below 32 MiB (glibc's own ceiling for its adaptive threshold) come from the heap, and
  // up to 128 MiB free at its top stay mapped: a FreeCAD session keeps at most that much beyond
  // what it used, in exchange for solves that do not fault their memory in again.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 128 << 20);
  mallopt(M_TOP_PAD, 16 << 20);
#endif
}

}  // namespace varsurf
