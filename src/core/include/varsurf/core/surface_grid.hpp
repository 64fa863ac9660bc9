// SPDX-License-Identifier: LGPL-2.1-or-later
// Points and unit normals of a surface on a uniform parameter grid: what the view draws while a
// sheet is dragged. Building a Part face and letting FreeCAD tessellate it took about 28 ms per
// move on a 64 x 64 pole sheet (measured in the GUI); this grid takes about a millisecond.
#pragma once

#include <Eigen/Core>

#include "varsurf/core/spline_space.hpp"

namespace varsurf {

struct SurfaceGrid {
  int nu = 0, nv = 0;        // cells per direction: (nu + 1) x (nv + 1) points
  Eigen::MatrixX3d points;   // row-major, u outer: point (i, j) is row i * (nv + 1) + j
  Eigen::MatrixX3d normals;  // unit S_u x S_v (a degenerate point copies a neighbour's)
};

// InvalidInput for an invalid surface or cell counts outside 1..2000.
SurfaceGrid sample_grid(const BSplineSurface& surface, int nu, int nv);

}  // namespace varsurf
