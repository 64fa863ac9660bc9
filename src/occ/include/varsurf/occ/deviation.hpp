// SPDX-License-Identifier: LGPL-2.1-or-later
// How far a target curve is from a sheet, measured by OCCT independently of the solver and of any
// pre-image: the true point-to-surface distance over the whole bounded sheet.
#pragma once

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf::occ {

// The largest distance from a point of `target` to the sheet (closest points inside it and on its
// boundary both count). The curve is sampled at least `samples` times evenly (>= 2), and besides in
// every knot span of the curve for its degree, more where it turns or its closest point crosses a
// surface patch; the largest local maxima are then refined between samples, so the figure hardly
// depends on `samples`.
double max_deviation(const BSplineSurface& surface, const BSplineCurve& target, int samples = 200);

}  // namespace varsurf::occ
