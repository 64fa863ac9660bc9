// SPDX-License-Identifier: LGPL-2.1-or-later
// Curvature continuity (G2) to a neighbouring face along a curve the sheet contains with G1.
//
// Where the sheet already shares the neighbour's tangent plane along the curve, the two second
// fundamental forms agree along the curve and in the mixed term; what is left is the normal
// curvature across it. At each sample the sheet's derivative across the pre-image, w_d, must
// satisfy N . w_dd = w_d^T K w_d, with N the neighbour's unit normal and K its second fundamental
// form extended to 3D (II(T, T) = T^T K T for tangent vectors T). The condition is quadratic in
// the poles: solve_sheet linearizes it at the current poles (Newton) and iterates.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/constraints.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf {

struct CurvatureConstraint {
  BSplineCurve preimage;  // 2D (u, v)
  BSplineCurve normals;   // 3D field N(t): the neighbour's normal (its sign fixes K's)
  // 6D field (K_xx, K_yy, K_zz, K_xy, K_xz, K_yz)(t): the neighbour's second fundamental form as
  // a symmetric 3D tensor, signed along N.
  BSplineCurve shape;
  double weight = 1.0;
};

// K from its six components.
Eigen::Matrix3d shape_tensor(const Eigen::VectorXd& six);

// Gauss samples along the pre-image (as for curve incidence), each one row of the condition
// linearized at `poles` (size() x 3): (N . b_dd - 2 (K w_d) . b_d) p = -w_d^T K w_d, coupled in x,
// y, z. Rows are scaled by |b_d| / |b_dd| so that they weigh like a ribbon's rows. InvalidInput
// for mismatched ranges, a pre-image leaving the domain or a sheet of degree below 3 (its
// second derivatives jump at every knot line).
ConstraintSamples sample_curvature(const SplineSpace& space, const CurvatureConstraint& c,
                                   const Eigen::MatrixX3d& poles);

// Largest |N . w_dd / |w_d|^2 - K(T, T)|, T = w_d / |w_d|, over `samples` parameters, relative to
// max(|k_sheet|, |k_neighbour|, floor): the curvature jump across the curve as the solver sees it.
// `rms`, if given, receives the root mean square of the same relative jumps.
double curvature_jump(const SplineSpace& space, const Eigen::MatrixX3d& poles,
                      const CurvatureConstraint& c, double floor, int samples = 200,
                      double* rms = nullptr);

}  // namespace varsurf
