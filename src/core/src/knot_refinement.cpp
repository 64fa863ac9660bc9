// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/knot_refinement.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"

namespace varsurf {

std::vector<double> dyadic_knots(const std::vector<double>& knots, int degree) {
  const int poles = static_cast<int>(knots.size()) - degree - 1;
  validate_knots(knots, degree, poles, "knots");
  std::vector<double> out;
  for (size_t i = 0; i < knots.size(); ++i) {
    out.push_back(knots[i]);
    if (i + 1 < knots.size() && knots[i + 1] > knots[i])
      out.push_back(0.5 * (knots[i] + knots[i + 1]));
  }
  return out;
}

Eigen::SparseMatrix<double> refinement_matrix(const std::vector<double>& coarse, int degree,
                                              const std::vector<double>& fine) {
  const int n = static_cast<int>(coarse.size()) - degree - 1;
  validate_knots(coarse, degree, n, "coarse knots");
  validate_knots(fine, degree, static_cast<int>(fine.size()) - degree - 1, "fine knots");
  if (coarse.front() != fine.front() || coarse.back() != fine.back())
    throw InvalidInput("refinement: the knot vectors must span the same domain");
  // The knots to insert: fine minus coarse, as multisets (both sorted).
  std::vector<double> extra;
  size_t c = 0;
  for (double t : fine) {
    if (c < coarse.size() && coarse[c] == t)
      ++c;
    else
      extra.push_back(t);
  }
  if (c != coarse.size())
    throw InvalidInput("refinement: the fine knot vector lacks a knot of the coarse one");
  // Rows of P are the control points of the curve whose components are the coarse basis
  // functions (P = identity); inserting knots one by one (Piegl & Tiller A5.1, one knot at a time)
  // turns them into the fine coefficients.
  std::vector<double> knots = coarse;
  Eigen::MatrixXd p = Eigen::MatrixXd::Identity(n, n);
  for (double t : extra) {
    const int count = static_cast<int>(p.rows());
    int k = static_cast<int>(std::upper_bound(knots.begin(), knots.end(), t) - knots.begin()) - 1;
    k = std::min(k, static_cast<int>(knots.size()) - degree - 2);  // t at the end: the last span
    Eigen::MatrixXd q(count + 1, n);
    for (int i = 0; i <= count; ++i) {
      if (i <= k - degree) {
        q.row(i) = p.row(i);
      } else if (i >= k + 1) {
        q.row(i) = p.row(i - 1);
      } else {
        const double a = (t - knots[static_cast<size_t>(i)]) /
                         (knots[static_cast<size_t>(i + degree)] - knots[static_cast<size_t>(i)]);
        q.row(i) = a * p.row(i) + (1.0 - a) * p.row(i - 1);
      }
    }
    knots.insert(knots.begin() + k + 1, t);
    p.swap(q);
  }
  return p.sparseView(1.0, 1e-15);
}

}  // namespace varsurf
