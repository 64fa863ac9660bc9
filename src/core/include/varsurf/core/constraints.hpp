// SPDX-License-Identifier: LGPL-2.1-or-later
// Geometric constraints on a sheet, all linear in the poles and separable in x, y, z.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf {

// The surface point at (u, v) must be `target`.
struct PointConstraint {
  double u = 0.0;
  double v = 0.0;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  double weight = 1.0;  // relative importance if constraints contradict each other
};

// Curve incidence (Welch & Witkin eq. 7): w(c(t)) = D(t) for t in [first, last], in least squares
// over the curve. `preimage` (dim 2) and `target` (dim 3) share the parameter t.
struct CurveConstraint {
  BSplineCurve preimage;
  BSplineCurve target;
  double weight = 1.0;  // relative importance if constraints contradict each other
  // Exact incidence: every direction the space can hold is fitted (only rank_tolerance
  // truncates), so a representable target is met to rounding. Otherwise the curve is fitted
  // until it is within SolveOptions::fit_tolerance, and the rest is left to fairness.
  bool exact = false;
};

// Weighted least-squares samples of constraints: row r says sqrt(w_r) * (b_r . x) = sqrt(w_r) *
// d_r. Separable samples act on the poles (columns = pole indices) with one right-hand side per
// coordinate (width 3); coupled samples act on the coordinates (column 3 k + c is coordinate c of
// pole k) with one right-hand side (width 1).
struct ConstraintSamples {
  std::vector<std::vector<int>> index;  // non-zero columns of each row
  std::vector<Eigen::VectorXd> coeff;   // their coefficients (already scaled by sqrt(w_r))
  Eigen::MatrixXd rhs;                  // scaled right-hand sides, rows x width
  std::vector<double> weight;           // w_r: what the row counts for in an RMS residual
  bool exact = false;                   // its cluster keeps every numerically independent row
  int rows() const { return static_cast<int>(index.size()); }
  bool coupled() const { return rhs.cols() == 1; }
};

// The same conditions on the coordinates: each separable row becomes three coupled rows.
ConstraintSamples to_coupled(const ConstraintSamples& separable);

// One row per point (weight as given).
ConstraintSamples sample_point(const SplineSpace& space, const PointConstraint& c);

// Gauss samples along the curve, split at pre-image knots and where the pre-image crosses the
// sheet's knot lines, so that each piece is polynomial and the quadrature is exact for polynomial
// pre-images. Weights are arc length of the target, normalized so the whole curve weighs `weight`.
// Throws InvalidInput if the pre-image leaves the sheet's domain.
ConstraintSamples sample_curve(const SplineSpace& space, const CurveConstraint& c);

// Where sample_curve samples: parameters and quadrature weights (before arc length). They depend
// on the pre-image and the target's knots only, so a target moved with the same knots reuses them.
struct CurveSampling {
  std::vector<double> t;
  std::vector<double> rule_weight;
};
CurveSampling curve_sampling(const SplineSpace& space, const CurveConstraint& c);

// sample_curve's right-hand sides and row weights for the target at the sampling's parameters;
// kept[k] is false for parameters dropped (no arc length there). No basis is evaluated.
void curve_rhs(const CurveConstraint& c, const CurveSampling& sampling, Eigen::MatrixXd& rhs,
               std::vector<double>& weights, std::vector<bool>& kept);

// sample_curve at a sampling already made (curve_sampling of the same space and constraint).
ConstraintSamples sample_curve(const SplineSpace& space, const CurveConstraint& c,
                               const CurveSampling& sampling);

// Largest |w(c(t)) - D(t)| over `samples` parameters evenly spaced on the curve: the incidence
// error as the solver sees it (through the pre-image).
double incidence_error(const SplineSpace& space, const Eigen::MatrixX3d& poles,
                       const CurveConstraint& c, int samples = 200);

}  // namespace varsurf
