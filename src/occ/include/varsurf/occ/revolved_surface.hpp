// SPDX-License-Identifier: LGPL-2.1-or-later
// Cylinders, cones, spheres and tori as exact rational B-spline surfaces that are smooth by their
// knots. OCCT's own conversion (GeomConvert, Convert_TgtThetaOver2) joins quadratic arcs at
// double knots: geometrically smooth, but C0 by multiplicity, so OCCT's Boolean argument check
// ("BOPAlgo GeomAbs_C0") refuses every face built on it, and a sheet solved on that space may
// crease there.
#pragma once

#include <Geom_BSplineSurface.hxx>
#include <Geom_Surface.hxx>

namespace varsurf::occ {

// `surface` (possibly a rectangular trim of one) over [u1, u2] x [v1, v2], built as the tensor
// product of its angular arc and its (radius, height) profile, both exact rational arcs of
// OCCT's Convert_QuasiAngular type (degree 6, no interior knot) or lines; the
// parameters are the surface's own on the box's sides. A surface of revolution (a revolved
// sketch) is its profile curve turned the same way, when that converts to a B-spline with its own
// parameter (B-splines, Béziers, lines). Null for any other surface, or a box longer than a
// period: the caller converts those another way.
Handle(Geom_BSplineSurface) smooth_revolved_surface(const Handle(Geom_Surface) & surface, double u1,
                                                    double u2, double v1, double v2);

}  // namespace varsurf::occ
