// SPDX-License-Identifier: LGPL-2.1-or-later
// Conversions between the core's B-splines and OCCT geometry. Knots are flat in the core and
// (value, multiplicity) pairs in OCCT; poles and weights map one to one (pole (i, j) of OCCT, both
// 1-based, is row (i-1) * nv + (j-1)). Periodic OCCT geometry is unperiodized.
#pragma once

#include <Geom2d_BSplineCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf::occ {

// Core -> OCCT. Validate first: InvalidInput for inconsistent data, GeometryError if OCCT still
// refuses (e.g. distinct knots closer than its resolution).
Handle(Geom_BSplineSurface) to_geom(const BSplineSurface& surface);
Handle(Geom_BSplineCurve) to_geom_curve(const BSplineCurve& curve);      // dim 3
Handle(Geom2d_BSplineCurve) to_geom2d_curve(const BSplineCurve& curve);  // dim 2

// OCCT -> core, on an unperiodized copy (the argument is left untouched). Null -> InvalidInput.
BSplineSurface from_geom(const Handle(Geom_BSplineSurface) & surface);
BSplineCurve from_geom(const Handle(Geom_BSplineCurve) & curve);
BSplineCurve from_geom(const Handle(Geom2d_BSplineCurve) & curve);

// The B-spline surface of any face, placed by the face's location and restricted to its UV bounds
// (the face's trimming is otherwise ignored). Cylinders, cones, spheres and tori are converted
// over that UV box with arcs smooth by their knots (smooth_revolved_surface), other surfaces by
// GeomConvert; each direction is reparametrized on its own, the box's sides mapping onto the
// result's. InvalidInput for null, unbounded or degenerate faces.
BSplineSurface surface_from_face(const TopoDS_Face& face);

// The 3D curve of an edge between its end parameters, placed by the edge's location, as a
// B-spline in the curve's own direction (edge orientation is ignored). InvalidInput for null,
// degenerated, curveless or zero-length edges.
BSplineCurve curve_from_edge(const TopoDS_Edge& edge);

}  // namespace varsurf::occ
