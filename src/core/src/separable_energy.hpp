// SPDX-License-Identifier: LGPL-2.1-or-later
// Quadratic energies of a polynomial tensor-product space whose integrand is a sum of products of
// separable derivative pairs: each term is a Kronecker product of the two directions' 1D Gram
// matrices, so no 2D quadrature is needed.
#pragma once

#include <Eigen/SparseCore>
#include <vector>

#include "varsurf/core/spline_space.hpp"

namespace varsurf {

// coef * int D^(au, av) phi_row * D^(bu, bv) phi_col (derivative orders along u and v).
struct SeparableTerm {
  double coef;
  int au, bu, av, bv;
};

// The symmetric matrix of the sum of `terms` (derivatives up to `order` <= 2) over the whole
// domain; exact. The space must be non-rational.
Eigen::SparseMatrix<double> assemble_separable(const SplineSpace& space,
                                               const std::vector<SeparableTerm>& terms, int order);

}  // namespace varsurf
