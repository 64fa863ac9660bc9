// SPDX-License-Identifier: LGPL-2.1-or-later
// The curvature of a sheet at a point (Du & Qin 4.7.3): the normal curvatures along u and v,
// kappa_u = N . w_uu / |w_u|^2 and kappa_v = N . w_vv / |w_v|^2, signed (positive: the sheet bends
// toward its normal N = w_u x w_v / |w_u x w_v|). Du & Qin set the curvature of the iso-lines,
// which also counts their geodesic bending within the surface (a matter of parametrization, not
// of shape); the normal curvature is the surface's own.
//
// The condition is not linear in the poles: solve_sheet linearizes it at the current poles, N held
// (as for G2 along curves), and iterates.
#pragma once

#include <Eigen/Core>

#include "varsurf/core/constraints.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf {

struct PointCurvatureConstraint {
  double u = 0.0;
  double v = 0.0;
  double kappa_u = 0.0;  // 1 / model unit
  double kappa_v = 0.0;
  bool along_u = true;  // which of the two are asked for
  bool along_v = true;
  double weight = 1.0;
};

// One row per direction asked, linearized at `poles` (size() x 3) with N held:
// (N . b_dd - 2 kappa w_d . b_d) p = -kappa |w_d|^2, coupled in x, y, z, scaled so that its
// coefficients weigh like a point row's. InvalidInput for a point outside the domain, no direction,
// non-finite targets, a sheet of degree below 2 or a point where w_u x w_v vanishes.
ConstraintSamples sample_point_curvature(const SplineSpace& space,
                                         const PointCurvatureConstraint& c,
                                         const Eigen::MatrixX3d& poles);

// The sheet's normal curvatures (kappa_u, kappa_v) at (u, v).
Eigen::Vector2d normal_curvatures(const SplineSpace& space, const Eigen::MatrixX3d& poles, double u,
                                  double v);

// Largest |kappa - target| over the directions asked, relative to max(|target|, floor): how far the
// sheet is from the condition, as the solver judges it.
double point_curvature_error(const SplineSpace& space, const Eigen::MatrixX3d& poles,
                             const PointCurvatureConstraint& c, double floor);

}  // namespace varsurf
