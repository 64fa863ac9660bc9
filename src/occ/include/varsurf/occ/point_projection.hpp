// SPDX-License-Identifier: LGPL-2.1-or-later
// Orthogonal projection of a point onto a sheet: where a picked vertex sits in (u, v).
#pragma once

#include <Eigen/Core>

#include "varsurf/core/spline_space.hpp"

namespace varsurf::occ {

struct PointOnSheet {
  double u = 0.0;
  double v = 0.0;
  double distance = 0.0;  // from the point to the sheet at (u, v)
};

// The closest point of the sheet (OCCT ShapeAnalysis_Surface, which also considers the boundary).
// InvalidInput for a non-finite point or an invalid sheet; GeometryError if OCCT fails.
PointOnSheet project_point(const BSplineSurface& sheet, const Eigen::Vector3d& point);

}  // namespace varsurf::occ
