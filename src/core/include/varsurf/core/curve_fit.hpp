// SPDX-License-Identifier: LGPL-2.1-or-later
// Least-squares fit of a clamped B-spline curve through parametrized points.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "varsurf/core/bspline_curve.hpp"

namespace varsurf {

// The clamped curve of `degree` on the flat `knots` that interpolates the first and last point and
// fits the others in the least-squares sense, each at its own parameter (`parameters` ascending,
// one row of `points` each, any dimension). Banded normal equations: well conditioned when every
// span holds samples. InvalidInput for mismatched sizes; SolveFailure when the system is
// singular (a span without samples).
BSplineCurve fit_clamped_curve(const std::vector<double>& parameters, const Eigen::MatrixXd& points,
                               int degree, const std::vector<double>& knots);

}  // namespace varsurf
