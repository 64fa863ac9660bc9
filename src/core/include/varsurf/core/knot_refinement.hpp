// SPDX-License-Identifier: LGPL-2.1-or-later
// Knot insertion as a linear map: a B-spline basis on a coarse knot vector written in the basis of
// a finer one (every coarse knot kept). Used to place refined layers and to export them exactly.
#pragma once

#include <Eigen/SparseCore>
#include <vector>

namespace varsurf {

// The coarse knot vector with the midpoint of every non-empty span inserted once: each span
// splits into two, span s becoming spans 2s and 2s + 1.
std::vector<double> dyadic_knots(const std::vector<double>& knots, int degree);

// T with N_coarse_j = sum_l T(l, j) N_fine_l (fine_count x coarse_count), by Boehm's insertion of
// each knot `fine` adds. InvalidInput unless both vectors are valid clamped vectors of `degree`
// and `fine` contains every knot of `coarse` (with at least its multiplicity).
Eigen::SparseMatrix<double> refinement_matrix(const std::vector<double>& coarse, int degree,
                                              const std::vector<double>& fine);

}  // namespace varsurf
