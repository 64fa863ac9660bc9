// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/curve_fit.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"

namespace varsurf {

BSplineCurve fit_clamped_curve(const std::vector<double>& parameters, const Eigen::MatrixXd& points,
                               int degree, const std::vector<double>& knots) {
  const int count = static_cast<int>(parameters.size());
  if (count < 2 || points.rows() != count || degree < 1)
    throw InvalidInput("curve fit: needs two or more points, one parameter each, degree >= 1");
  const int n = static_cast<int>(knots.size()) - degree - 1;
  if (n < 2) throw InvalidInput("curve fit: the knot vector holds fewer than two poles");
  BSplineCurve c;
  c.degree = degree;
  c.knots = knots;
  const Eigen::RowVectorXd first = points.row(0), last = points.row(count - 1);
  c.poles = Eigen::MatrixXd::Zero(n, points.cols());
  c.poles.row(0) = first;
  c.poles.row(n - 1) = last;
  if (n == 2) return c;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n - 2, points.cols());
  Eigen::MatrixXd basis(1, degree + 1);
  for (int i = 1; i + 1 < count; ++i) {
    const double t = parameters[static_cast<size_t>(i)];
    const int span = find_span(knots, degree, t);
    basis_derivatives(knots, degree, span, t, 0, basis);
    Eigen::RowVectorXd r = points.row(i);
    for (int j = 0; j <= degree; ++j) {
      const int col = span - degree + j;
      if (col == 0) r -= basis(0, j) * first;
      if (col == n - 1) r -= basis(0, j) * last;
    }
    for (int j = 0; j <= degree; ++j) {
      const int cj = span - degree + j;
      if (cj == 0 || cj == n - 1) continue;
      rhs.row(cj - 1) += basis(0, j) * r;
      for (int k = 0; k <= degree; ++k) {
        const int ck = span - degree + k;
        if (ck == 0 || ck == n - 1) continue;
        entries.emplace_back(cj - 1, ck - 1, basis(0, j) * basis(0, k));
      }
    }
  }
  Eigen::SparseMatrix<double> normal(n - 2, n - 2);
  normal.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(normal);
  if (ldlt.info() != Eigen::Success)
    throw SolveFailure("curve fit: singular (too few samples per span)");
  c.poles.middleRows(1, n - 2) = ldlt.solve(rhs);
  if (!c.poles.allFinite()) throw SolveFailure("curve fit: singular (too few samples per span)");
  return c;
}

}  // namespace varsurf
