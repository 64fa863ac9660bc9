// SPDX-License-Identifier: LGPL-2.1-or-later
#include "serial_openmp.hpp"

#include <omp.h>

namespace varsurf {

// No active level: every parallel region opened by this thread runs on it alone. The setting
// belongs to the calling thread (libgomp keeps it per thread; the guard's test checks that), and
// is put back when the guard ends, so FreeCAD's other OpenMP users keep theirs.
SerialOpenMp::SerialOpenMp() : saved_levels_(omp_get_max_active_levels()) {
  omp_set_max_active_levels(0);
}

SerialOpenMp::~SerialOpenMp() {
  omp_set_max_active_levels(saved_levels_);
}

}  // namespace varsurf
