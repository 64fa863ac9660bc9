// SPDX-License-Identifier: LGPL-2.1-or-later
// The energy whose Euler-Lagrange equation is the generalized Bloor-Wilson PDE (Du & Qin eq. 1):
// E(P) = int_[0,1]^2 |P_ss + a(s, t)^2 P_tt|^2 ds dt in the normalized parameters s, t of the
// sheet's domain, per coordinate, as the quadratic form p^T H p on the sheet's spline space (the
// B-spline finite elements of Du & Qin 4.9). For constant a its minimizers satisfy
// (d^2/ds^2 + a^2 d^2/dt^2)^2 P = 0 inside; for a varying a the Galerkin form is that of
// L* L P = 0 with L = d^2/ds^2 + a^2 d^2/dt^2 (the paper's finite differences apply L twice).
#pragma once

#include <Eigen/SparseCore>

#include "varsurf/core/pde_coefficient.hpp"
#include "varsurf/core/region.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf {

// Exact for non-rational spaces when a is constant (Kronecker products of 1D Gram matrices) or a
// B-spline field of degree q (Gauss rules of degree + 2q + 1 points per span and direction), and
// for sharp painted regions over a constant a that do not overlap (each region's own quadrature).
// A blended border is integrated with 4 more points per direction; rational spaces get 2 more.
Eigen::SparseMatrix<double> assemble_pde(const SplineSpace& space, const PdeCoefficient& a);

// The energy of a trimmed sheet, as assemble_thin_plate's: the PDE energy over `region` plus
// `outside` (in [0, 1)) times that over the rest of the domain.
Eigen::SparseMatrix<double> assemble_pde(const SplineSpace& space, const PdeCoefficient& a,
                                         const Region& region, double outside);

}  // namespace varsurf
