// SPDX-License-Identifier: LGPL-2.1-or-later
// Fairness of a space curve (Welch & Witkin sec. 5: variational curves shared by sheets):
// integral over t of stretch |C'(t)|^2 + bend |C''(t)|^2, a quadratic form in the poles.
#pragma once

#include <Eigen/SparseCore>

#include "varsurf/core/bspline_curve.hpp"

namespace varsurf {

// H (pole_count x pole_count, per coordinate) with E = sum_c P_c^T H P_c, exact by Gauss
// quadrature on every span. InvalidInput for a rational curve, negative or non-finite weights,
// or both weights zero.
Eigen::SparseMatrix<double> assemble_curve_energy(const BSplineCurve& curve, double stretch,
                                                  double bend);

}  // namespace varsurf
