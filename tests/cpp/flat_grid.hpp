// SPDX-License-Identifier: LGPL-2.1-or-later
// A flat square quad grid in the xy plane: the control mesh the multiresolution tests capture
// their reliefs onto and draw their curves across.
#pragma once

#include "varsurf/core/subdivision.hpp"

namespace varsurf::test {

// cells x cells quads of side `spacing`, corners at 0 and cells * spacing; vertex i * (cells + 1)
// + j at (i * spacing, j * spacing, 0).
inline SubdivisionMesh flat_grid(int cells, double spacing) {
  SubdivisionMesh m;
  const int n = cells + 1;
  m.points.resize(n * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) m.points.row(i * n + j) << i * spacing, j * spacing, 0.0;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j)
      m.faces.push_back({i * n + j, (i + 1) * n + j, (i + 1) * n + j + 1, i * n + j + 1});
  return m;
}

}  // namespace varsurf::test
