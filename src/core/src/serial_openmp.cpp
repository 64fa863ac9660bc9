// SPDX-License-Identifier: LGPL-2.1-or-later
#include "serial_openmp.hpp"

#include <omp.h>

namespace varsurf {

// No active level: every parallel region runs on the thread that opens it. The setting is the
// process's, so it is put back when the guard ends (FreeCAD's other OpenMP users keep theirs).
SerialOpenMp::SerialOpenMp() : saved_levels_(omp_get_max_active_levels()) {
  omp_set_max_active_levels(0);
}

SerialOpenMp::~SerialOpenMp() {
  omp_set_max_active_levels(saved_levels_);
}

}  // namespace varsurf
