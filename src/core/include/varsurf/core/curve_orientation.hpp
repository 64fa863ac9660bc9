// SPDX-License-Identifier: LGPL-2.1-or-later
// A curve's parameter changed without changing its points: reversed, moved onto another range
// (affinely: exact), turned to run the way two given ends ask, or cut to a piece of its range
// (by knot insertion: exact). A map between two curves
// (a PDE surface's boundary rows, a CurveMap constraint) pairs their points by parameter.
#pragma once

#include <Eigen/Core>

#include "varsurf/core/bspline_curve.hpp"

namespace varsurf {

// The curve with its parameter reversed (same points, same range).
BSplineCurve reversed(const BSplineCurve& c);

// The same points on [t0, t1]: the knots mapped affinely. InvalidInput unless t0 < t1, finite.
BSplineCurve on_range(const BSplineCurve& c, double t0, double t1);

// c, or c reversed, whichever pairs its start with `start` and its end with `end` better (the
// smaller sum of the two distances; c on a tie). InvalidInput for points of another dimension.
BSplineCurve oriented(const BSplineCurve& c, const Eigen::VectorXd& start,
                      const Eigen::VectorXd& end);

// The part of c on [t0, t1] (first() <= t0 < t1 <= last()), on that same range: both ends
// inserted to full multiplicity, rational curves in homogeneous form. InvalidInput otherwise.
BSplineCurve piece(const BSplineCurve& c, double t0, double t1);

}  // namespace varsurf
