// SPDX-License-Identifier: LGPL-2.1-or-later
// How far an edge's 3D curve and its curve on a face part, as OCCT's own curve-on-surface check
// (the one its Boolean operations run) measures it: what an edge's tolerance must cover.
#pragma once

#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <vector>

namespace varsurf::occ {

// On one face: the largest distance between the 3D curve and the pcurve; -1 if OCCT cannot
// measure it (no pcurve, no 3D curve).
double curve_on_surface_deviation(const TopoDS_Edge& edge, const TopoDS_Face& face);

// The largest over the faces; faces where it cannot be measured count 0.
double curve_on_surface_deviation(const TopoDS_Edge& edge, const std::vector<TopoDS_Face>& faces);

}  // namespace varsurf::occ
