// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/bspline_curve.hpp"

#include <cmath>
#include <string>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"

namespace varsurf {

void BSplineCurve::validate(const char* what) const {
  const std::string w(what);
  if (poles.rows() == 0 || poles.cols() == 0) throw InvalidInput(w + ": has no poles");
  validate_knots(knots, degree, pole_count(), what);
  if (!poles.allFinite()) throw InvalidInput(w + ": pole coordinates are not finite");
  if (rational()) {
    if (weights.size() != poles.rows()) throw InvalidInput(w + ": one weight per pole expected");
    if (!weights.allFinite() || (weights.array() <= 0.0).any())
      throw InvalidInput(w + ": weights must be finite and positive");
  }
}

Eigen::MatrixXd BSplineCurve::derivatives(double t, int order) const {
  if (order < 0 || order > 2) throw InvalidInput("curve derivatives: order must be 0, 1 or 2");
  const int p = degree;
  const int span = find_span(knots, p, t);
  const int first = span - p;
  // Stack buffers for the usual degrees and dimensions: every constraint sample and projection
  // evaluates here (heap blocks were a third of a curve sample's cost, perf).
  using Basis = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, kStackDegree + 1>;
  using Rows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>;
  if (p > kStackDegree || dim() > 3) return derivatives_general(t, order);
  Basis n(order + 1, p + 1);
  basis_derivatives(knots, p, span, t, order, n);
  if (!rational()) return n * poles.middleRows(first, p + 1);
  // Homogeneous derivatives A^(k) and W^(k), then the quotient rule (Piegl & Tiller A4.2).
  for (int i = 0; i <= p; ++i) n.col(i) *= weights(first + i);
  const Rows a = n * poles.middleRows(first, p + 1);
  Eigen::Matrix<double, 3, 1> w = Eigen::Matrix<double, 3, 1>::Zero();
  for (int k = 0; k <= order; ++k) w(k) = n.row(k).sum();
  Eigen::MatrixXd c(order + 1, dim());
  for (int k = 0; k <= order; ++k) {
    c.row(k) = a.row(k);
    for (int i = 1; i <= k; ++i) {
      const double binom = (k == 2 && i == 1) ? 2.0 : 1.0;
      c.row(k) -= binom * w(i) * c.row(k - i);
    }
    c.row(k) /= w(0);
  }
  return c;
}

Eigen::MatrixXd BSplineCurve::derivatives_general(double t, int order) const {
  const int p = degree;
  const int span = find_span(knots, p, t);
  Eigen::MatrixXd n(order + 1, p + 1);
  basis_derivatives(knots, p, span, t, order, n);
  const int first = span - p;
  if (!rational()) {
    return n * poles.middleRows(first, p + 1);
  }
  const Eigen::VectorXd w = weights.segment(first, p + 1);
  Eigen::MatrixXd nw = n * w.asDiagonal();
  Eigen::MatrixXd a = nw * poles.middleRows(first, p + 1);
  Eigen::VectorXd wd = nw.rowwise().sum();
  Eigen::MatrixXd c(order + 1, dim());
  for (int k = 0; k <= order; ++k) {
    Eigen::RowVectorXd v = a.row(k);
    for (int i = 1; i <= k; ++i) {
      const double binom = (k == 2 && i == 1) ? 2.0 : 1.0;
      v -= binom * wd(i) * c.row(k - i);
    }
    c.row(k) = v / wd(0);
  }
  return c;
}

Eigen::VectorXd BSplineCurve::evaluate(double t) const {
  return derivatives(t, 0).row(0).transpose();
}

}  // namespace varsurf
