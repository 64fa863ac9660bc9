// SPDX-License-Identifier: LGPL-2.1-or-later
// How far a target curve is from a sheet, measured by OCCT independently of the solver and of any
// pre-image: the true point-to-surface distance over the whole bounded sheet.
#pragma once

#include <limits>
#include <vector>

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf::occ {

// The largest distance from a point of `target` to the sheet (closest points inside it and on its
// boundary both count). The curve is sampled at least `samples` times evenly (>= 2), and besides in
// every knot span of the curve for its degree, more where it turns or its closest point crosses a
// surface patch; the largest local maxima are then refined between samples, so the figure hardly
// depends on `samples`.
//
// With `accept` > 0, a sample that Newton from its neighbour's closest point finds within
// `accept` of the sheet skips the global search (which proves that no other part of the sheet is
// nearer, and costs 10 to 100 times as much); such an answer can only overstate the true one, so
// the largest of them are searched globally until a global one exceeds all that are left, and
// the refined peaks are global too: the same figure, found 10 times faster where the sheet meets
// the curve. On a sheet folded over itself Newton can track another fold: the figure may then
// overstate (never understate) the distance.
double max_deviation(const BSplineSurface& surface, const BSplineCurve& target, int samples = 200,
                     double accept = 0.0);

// max_deviation of each target from one sheet, sharing the sheet's search structure.
//
// With a finite `stop_above` (for a caller that only goes on when every curve is within it, such
// as a refinement round): the first curve found farther than stop_above ends the measure. Its
// figure is then the first distance proven beyond stop_above (a global one, not necessarily its
// largest) and the curves after it are not measured (infinity). A sheet that misses the tolerance
// sends most of its samples to the global search, and measuring it whole was 40 % of a refining
// recompute (benchmark 2's last case: 76 of 190 ms).
std::vector<double> max_deviations(const BSplineSurface& surface,
                                   const std::vector<BSplineCurve>& targets, int samples = 200,
                                   double accept = 0.0,
                                   double stop_above = std::numeric_limits<double>::infinity());

}  // namespace varsurf::occ
