// SPDX-License-Identifier: LGPL-2.1-or-later
// A (possibly rational) B-spline curve in any dimension: used for 3D target curves and for 2D
// pre-images in a sheet's (u, v) domain.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace varsurf {

struct BSplineCurve {
  int degree = 0;
  std::vector<double> knots;  // flat, clamped, size = pole_count + degree + 1
  Eigen::MatrixXd poles;      // pole_count x dim
  Eigen::VectorXd weights;    // empty for a non-rational curve, else pole_count positive values

  int dim() const { return static_cast<int>(poles.cols()); }
  int pole_count() const { return static_cast<int>(poles.rows()); }
  bool rational() const { return weights.size() > 0; }
  double first() const { return knots.front(); }
  double last() const { return knots.back(); }

  // Throws InvalidInput with `what` in the message if the data is inconsistent or not finite.
  void validate(const char* what = "curve") const;

  // Point and derivatives at t: row k is the k-th derivative, k = 0..order (order <= 2).
  Eigen::MatrixXd derivatives(double t, int order) const;
  Eigen::VectorXd evaluate(double t) const;

 private:
  // derivatives() with heap work arrays: degrees above kStackDegree, more than 3 dimensions.
  Eigen::MatrixXd derivatives_general(double t, int order) const;
};

}  // namespace varsurf
