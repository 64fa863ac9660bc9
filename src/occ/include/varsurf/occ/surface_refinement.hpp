// SPDX-License-Identifier: LGPL-2.1-or-later
// Uniform refinement of a sheet's B-spline space by knot insertion: the surface is unchanged,
// the space gains the freedom a variational solve needs to hold curves that do not follow its
// iso lines.
#pragma once

#include "varsurf/core/spline_space.hpp"

namespace varsurf::occ {

// The same surface with its degree raised to at least min_degree in both directions (OCCT
// IncreaseDegree: planes convert to bilinear NURBS, which cannot carry a bending energy) and knots
// inserted (InsertUKnots/InsertVKnots) so that each direction has at least min_spans_u /
// min_spans_v polynomial spans, the longest intervals halved first. InvalidInput for span counts
// outside 1..4096 or a degree outside 1..9.
BSplineSurface refine_surface(const BSplineSurface& surface, int min_spans_u, int min_spans_v,
                              int min_degree = 1);

}  // namespace varsurf::occ
