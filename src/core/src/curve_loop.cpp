// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/curve_loop.hpp"

#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf {

namespace {

Eigen::VectorXd end_of(const BSplineCurve& c, bool last) {
  return c.evaluate(last ? c.last() : c.first());
}

}  // namespace

CurveLoop chain_loop(const std::vector<BSplineCurve>& curves, double gap) {
  if (curves.empty()) throw InvalidInput("the boundary loop has no curves");
  for (const BSplineCurve& c : curves) {
    c.validate("boundary curve");
    if (c.dim() != 2) throw InvalidInput("boundary curves must be 2D (u, v) curves");
  }
  CurveLoop loop;
  std::vector<bool> used(curves.size(), false);
  loop.steps.push_back({0, false});
  used[0] = true;
  Eigen::VectorXd at = end_of(curves[0], true);
  for (size_t n = 1; n < curves.size(); ++n) {
    double best = 1e300;
    LoopStep pick;
    for (size_t i = 0; i < curves.size(); ++i) {
      if (used[i]) continue;
      for (bool reversed : {false, true}) {
        const double d = (end_of(curves[i], reversed) - at).norm();
        if (d < best) best = d, pick = {static_cast<int>(i), reversed};
      }
    }
    if (best > gap)
      throw InvalidInput("the boundary loop does not close: a gap of " + std::to_string(best) +
                         " in (u, v) after curve " + std::to_string(loop.steps.back().curve));
    used[static_cast<size_t>(pick.curve)] = true;
    loop.steps.push_back(pick);
    at = end_of(curves[static_cast<size_t>(pick.curve)], !pick.reversed);
  }
  const double closing = (at - end_of(curves[0], false)).norm();
  if (closing > gap)
    throw InvalidInput("the boundary loop does not close: a gap of " + std::to_string(closing) +
                       " in (u, v) between its last and first curves");
  // Shoelace on samples of each curve, walked in loop order.
  const int n = 64;
  for (const LoopStep& step : loop.steps) {
    const BSplineCurve& c = curves[static_cast<size_t>(step.curve)];
    auto point = [&](int k) {
      const double f = static_cast<double>(step.reversed ? n - k : k) / n;
      return c.evaluate(c.first() + (c.last() - c.first()) * f);
    };
    Eigen::VectorXd prev = point(0);
    for (int k = 1; k <= n; ++k) {
      const Eigen::VectorXd p = point(k);
      loop.signed_area += 0.5 * (prev(0) * p(1) - p(0) * prev(1));
      prev = p;
    }
  }
  const int ccw = loop.signed_area > 0.0 ? 1 : -1;
  for (LoopStep& step : loop.steps) step.inside = step.reversed ? -ccw : ccw;
  return loop;
}

}  // namespace varsurf
