// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/curve_orientation.hpp"

#include <algorithm>
#include <cmath>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_refinement.hpp"

namespace varsurf {

BSplineCurve reversed(const BSplineCurve& c) {
  c.validate("curve");
  BSplineCurve r = c;
  const double a = c.first(), b = c.last();
  for (size_t k = 0; k < c.knots.size(); ++k) r.knots[k] = a + b - c.knots[c.knots.size() - 1 - k];
  r.poles = c.poles.colwise().reverse();
  if (c.rational()) r.weights = c.weights.reverse();
  return r;
}

BSplineCurve on_range(const BSplineCurve& c, double t0, double t1) {
  c.validate("curve");
  if (!(std::isfinite(t0) && std::isfinite(t1) && t0 < t1))
    throw InvalidInput("a curve's new parameter range must be finite with its start below its end");
  const double a = c.first(), b = c.last();
  if (!(a < b)) throw InvalidInput("the curve's own parameter range is empty");
  BSplineCurve r = c;
  // The clamped end knots exactly at t0 and t1, whatever the rounding of the map.
  for (double& k : r.knots) k = k == a ? t0 : k == b ? t1 : t0 + (k - a) / (b - a) * (t1 - t0);
  return r;
}

BSplineCurve oriented(const BSplineCurve& c, const Eigen::VectorXd& start,
                      const Eigen::VectorXd& end) {
  c.validate("curve");
  if (start.size() != c.dim() || end.size() != c.dim())
    throw InvalidInput("the ends a curve is turned toward must have the curve's dimension");
  const Eigen::VectorXd first = c.evaluate(c.first()), last = c.evaluate(c.last());
  const double kept = (first - start).norm() + (last - end).norm();
  const double turned = (last - start).norm() + (first - end).norm();
  return turned < kept ? reversed(c) : c;
}

BSplineCurve piece(const BSplineCurve& c, double t0, double t1) {
  c.validate("curve");
  if (!(std::isfinite(t0) && std::isfinite(t1) && c.first() <= t0 && t0 < t1 && t1 <= c.last()))
    throw InvalidInput(
        "a curve's piece must lie within its parameter range, its start below its end");
  const int p = c.degree;
  // Each end to multiplicity p (the clamped ends have p + 1 already): there the curve is a pole.
  std::vector<double> fine = c.knots;
  for (double t : {t0, t1}) {
    const auto have = std::count(c.knots.begin(), c.knots.end(), t);
    fine.insert(std::upper_bound(fine.begin(), fine.end(), t), std::max<long>(0, p - have), t);
  }
  const Eigen::SparseMatrix<double> map = refinement_matrix(c.knots, p, fine);
  Eigen::MatrixXd homogeneous(c.pole_count(), c.dim() + 1);
  const Eigen::VectorXd w = c.rational() ? c.weights : Eigen::VectorXd::Ones(c.pole_count());
  homogeneous.leftCols(c.dim()) = c.poles.array().colwise() * w.array();
  homogeneous.col(c.dim()) = w;
  const Eigen::MatrixXd refined = map * homogeneous;
  // The last p copies of t0 start the piece, the first p copies of t1 end it.
  const auto last0 = std::upper_bound(fine.begin(), fine.end(), t0) - fine.begin() - 1;
  const auto first1 = std::lower_bound(fine.begin(), fine.end(), t1) - fine.begin();
  const auto i = last0 - p + 1, j = first1;
  BSplineCurve out;
  out.degree = p;
  out.knots.push_back(t0);
  out.knots.insert(out.knots.end(), fine.begin() + i, fine.begin() + j + p);
  out.knots.push_back(t1);
  const Eigen::MatrixXd h = refined.middleRows(i - 1, j - i + 1);
  out.poles = h.leftCols(c.dim()).array().colwise() / h.col(c.dim()).array();
  if (c.rational()) out.weights = h.col(c.dim());
  return out;
}

}  // namespace varsurf
