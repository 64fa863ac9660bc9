// SPDX-License-Identifier: LGPL-2.1-or-later
// Thin plate under tension (Welch & Witkin eq. 4): sum_ij alpha_ij D_i w D_j w + beta_ij (D_i D_j
// w)^2 integrated over the parameter domain, as the quadratic form p^T H p per coordinate.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "varsurf/core/region.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf {

struct ThinPlateWeights {
  Eigen::Matrix2d alpha = Eigen::Matrix2d::Identity();  // stretch: symmetric, PSD
  Eigen::Matrix2d beta = Eigen::Matrix2d::Ones();       // bend: beta_ij weights (D_i D_j w)^2

  // alpha_ij = a delta_ij and beta_ij = b for all i, j: the classic w_uu^2 + 2 w_uv^2 + w_vv^2.
  static ThinPlateWeights isotropic(double stretch, double bend);
  void validate() const;  // throws InvalidInput for negative, non-finite or asymmetric weights
};

// Exact for non-rational spaces (Gauss rule of degree+1 points per span and direction); rational
// spaces use two more points per direction.
Eigen::SparseMatrix<double> assemble_thin_plate(const SplineSpace& space,
                                                const ThinPlateWeights& w);

// The energy of a trimmed sheet: the thin plate over `region` (the part that is kept) plus
// `outside` (in [0, 1)) times the thin plate over the rest of the domain. A small `outside` keeps
// the overhang from pulling on the kept part, while the poles that act only outside stay
// determined and the overhang smooth (the face's pcurves are computed on it). The region's
// quadrature is exact like the whole domain's (region_quadrature).
Eigen::SparseMatrix<double> assemble_thin_plate(const SplineSpace& space, const ThinPlateWeights& w,
                                                const Region& region, double outside);

}  // namespace varsurf
