// How far a target curve is from a sheet, measured by OCCT independently of the solver and of any
// pre-image: the true point-to-surface distance over the whole bounded sheet.
#pragma once

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf::occ {

// Max over `samples` evenly spaced target parameters of the minimum distance to the sheet
// (interior projections and the closest boundary point both count). samples >= 2.
double max_deviation(const BSplineSurface& surface, const BSplineCurve& target, int samples = 200);

}  // namespace varsurf::occ
