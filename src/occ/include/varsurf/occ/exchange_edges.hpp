// SPDX-License-Identifier: LGPL-2.1-or-later
// Edges prepared for a file that stores no tolerances (STEP).
//
// An edge shared by two sheets that meet only within a tolerance has a 3D curve and pcurves
// that disagree by up to that tolerance. STEP keeps the curves but not the tolerance: a reader
// re-derives it by sampling the deviation (OCCT's reader: 23 evenly spaced parameters per edge,
// plus 1e-5 relative), so a peak between samples is missed and the re-read edge fails the
// curve-on-surface check of OCCT's Boolean operations. Splitting an edge where its deviation
// peaks puts every peak on a vertex, where any reader measures it.
#pragma once

#include <TopoDS_Shape.hxx>

namespace varsurf::occ {

struct ExchangeShape {
  TopoDS_Shape shape;
  double max_deviation = 0.0;  // largest 3D-curve / pcurve distance over all edges
  int split_edges = 0;         // edges split at their deviation's peaks
};

// The shape with each edge whose deviation exceeds OCCT's confusion (1e-7) split where the
// deviation peaks, until on every piece it is largest at the ends (interior peaks stay 0.1 %
// below: a reader's re-parametrisation moves them by less), except where a piece would come out
// shorter than 20 times the largest deviation (a reader removes edges shorter than the file's
// uncertainty; step_io writes twice the deviation). Geometry is unchanged: the pieces
// keep the edge's curves; the new vertices' tolerances cover the deviation there. Edges on a
// surface's seam are left as they are; B-spline curves are cut exactly, others (lines, circles)
// shared with a narrower range. A null shape is
// returned unchanged.
ExchangeShape prepare_for_exchange(const TopoDS_Shape& shape);

// The reading side: raises every edge tolerance that falls short of the 3D-curve / pcurve
// deviation OCCT's curve-on-surface check measures (as its Boolean operations do), and vertex
// tolerances to match; returns how many edges were raised. A re-read file from any writer then
// passes that check. The shape's geometry is not touched.
int cover_measured_deviations(const TopoDS_Shape& shape);

}  // namespace varsurf::occ
