// SPDX-License-Identifier: LGPL-2.1-or-later
// Closed sheets: a clamped space whose two ends along u (or v) are one seam. The sheet's position
// and its derivatives across the seam are tied equal on both sides, up to order degree - 1 for a
// polynomial space (a periodic spline: the seam is like any simple knot line, and the sheet does
// not depend on where it is) and min(2, degree - 1) for a rational one, so the seam is an interior
// curve of the closed surface: the energy and the constraints treat it like any other. The solve
// ties the displacement from its start shape (the rows' right-hand side is the start's own
// mismatch): a base whose parametrization is only C1 across its seam, as a cylinder's rational
// circles, keeps its own seam plus a smooth change. The result exports as a closed (seam-split)
// B-spline face.
#pragma once

#include <Eigen/Core>
#include <map>
#include <vector>

#include "varsurf/core/constraints.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf {

// The ties of the seam along `direction` (0: the space is closed along u, its u ends meet; 1:
// along v), at the Greville abscissae of the other direction (where a spline of the other
// direction is determined by its values; polynomial spaces: per pole of the other direction):
// separable, exact rows, each scaled to unit length (their derivative factors grow like
// p! / (p - k)!). Rows whose poles are all `fixed` (flags per pole, or empty) are left out:
// nothing can move to meet them.
// A clamped spline of `degree` on `knots` closed on itself: per order k = 0 .. max_order, the
// coefficients (coefficient index -> value) of its k-th derivative at the first end minus that at
// the last, scaled to a unit row (the factors grow like p! / (p - k)!: beside a degree-14 loft's
// order-13 rows the position rows fell under the reduction's rank tolerance). Shared by a closed
// sheet's pole lines and a closed space curve.
std::vector<std::map<int, double>> closure_rows(const std::vector<double>& knots, int degree,
                                                int max_order);

ConstraintSamples sample_seam(const SplineSpace& space, int direction,
                              const std::vector<bool>& fixed = {});

// The highest derivative order (0 .. what sample_seam ties) up to which `poles` are already
// continuous across the seam along `direction` (every lower order too), each derivative scaled
// as in sample_seam and compared with `tolerance` times the poles' extent at `samples` points;
// -1 when the two ends do not meet. What a closed base face asks its sheet's seam to keep.
int seam_continuity(const SplineSpace& space, const Eigen::MatrixX3d& poles, int direction,
                    double tolerance = 1e-9, int samples = 100);

// Largest |d^k w / d^k s (first) - d^k w / d^k s (last)| over k = 0 .. min(2, order tied) and
// `samples` points along the seam, each derivative scaled as in sample_seam: how far the seam is
// from closed (0 for a closed sheet, up to rounding).
double seam_mismatch(const SplineSpace& space, const Eigen::MatrixX3d& poles, int direction,
                     int samples = 100);

}  // namespace varsurf
