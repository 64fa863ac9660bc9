// SPDX-License-Identifier: LGPL-2.1-or-later
// Normal fields along a curve: what a ribbon (or a G1 join) asks the sheet's normal to follow.
#pragma once

#include <TopoDS_Face.hxx>

#include "varsurf/core/bspline_curve.hpp"

namespace varsurf::occ {

// N(t) over the curve's parameter range: at sample parameters, the reference face's outward
// normal (face orientation respected) at the point closest to curve(t), turned by `angle_deg`
// about the curve's tangent; fitted by a cubic B-spline through the samples at their own t
// (GeomAPI_PointsToBSpline). InvalidInput if the curve is farther than `max_distance` from the
// face, or for invalid data; GeometryError if OCCT fails.
BSplineCurve normal_field(const TopoDS_Face& reference, const BSplineCurve& curve, double angle_deg,
                          double max_distance, int samples = 0);

// N(t) of the ruled strip from `curve` to a second curve: at each sample, the normal of the
// plane spanned by the curve's tangent and the direction to the second curve's closest point,
// turned by `angle_deg` about the tangent. InvalidInput where the curves touch or the direction
// runs along the tangent.
BSplineCurve normal_field_between(const BSplineCurve& curve, const BSplineCurve& second,
                                  double angle_deg, int samples = 0);

}  // namespace varsurf::occ
