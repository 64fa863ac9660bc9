// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/curve_orientation.hpp"

#include <cmath>

#include "varsurf/core/errors.hpp"

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

}  // namespace varsurf
