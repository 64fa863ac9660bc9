// SPDX-License-Identifier: LGPL-2.1-or-later
// A curve's parameter changed without moving its points: reversed, on another range, turned
// toward two ends. Checked point for point against the original curve.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "varsurf/core/curve_orientation.hpp"
#include "varsurf/core/errors.hpp"

using namespace varsurf;

namespace {

// A rational quadratic quarter circle of radius 10 on [2, 5] with an interior knot at 3.
BSplineCurve arc() {
  BSplineCurve c;
  c.degree = 2;
  c.knots = {2, 2, 2, 3, 5, 5, 5};
  c.poles.resize(4, 3);
  c.poles << 10, 0, 0, 10, 4, 1, 6, 10, 2, 0, 10, 3;
  c.weights.resize(4);
  c.weights << 1.0, 0.8, 0.9, 1.0;
  return c;
}

}  // namespace

TEST(CurveOrientation, ReversedRunsThroughTheSamePointsBackwards) {
  const BSplineCurve c = arc(), r = reversed(c);
  EXPECT_EQ(r.first(), 2.0);
  EXPECT_EQ(r.last(), 5.0);
  for (int k = 0; k <= 30; ++k) {
    const double t = 2.0 + 3.0 * k / 30.0;
    EXPECT_LT((r.evaluate(7.0 - t) - c.evaluate(t)).norm(), 1e-12) << t;
  }
  EXPECT_EQ(reversed(r).poles, c.poles);
}

TEST(CurveOrientation, OnRangeMapsTheParameterAffinely) {
  const BSplineCurve c = arc(), r = on_range(c, -1.0, 0.5);
  // The clamped end knots exactly at the new ends: the curve stays valid.
  EXPECT_EQ(r.knots.front(), -1.0);
  EXPECT_EQ(r.knots[2], -1.0);
  EXPECT_EQ(r.knots.back(), 0.5);
  EXPECT_EQ(r.knots[4], 0.5);
  EXPECT_NO_THROW(r.validate());
  for (int k = 0; k <= 30; ++k) {
    const double s = k / 30.0;
    EXPECT_LT((r.evaluate(-1.0 + 1.5 * s) - c.evaluate(2.0 + 3.0 * s)).norm(), 1e-12) << s;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(on_range(c, 1.0, 1.0), InvalidInput);
  EXPECT_THROW(on_range(c, 1.0, 0.0), InvalidInput);
  EXPECT_THROW(on_range(c, nan, 1.0), InvalidInput);
  EXPECT_THROW(on_range(BSplineCurve(), 0.0, 1.0), InvalidInput);
}

TEST(CurveOrientation, OrientedTurnsTowardTheNearerEnds) {
  const BSplineCurve c = arc();
  const Eigen::VectorXd a = c.evaluate(2.0), b = c.evaluate(5.0);
  const Eigen::Vector3d off(0.5, -0.3, 0.2);
  EXPECT_EQ(oriented(c, a + off, b - off).poles, c.poles);
  EXPECT_EQ(oriented(c, b + off, a - off).poles, reversed(c).poles);
  // A tie keeps the curve as it is.
  const Eigen::VectorXd mid = 0.5 * (a + b);
  EXPECT_EQ(oriented(c, mid, mid).poles, c.poles);
  EXPECT_THROW(oriented(c, Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1)), InvalidInput);
}

// A piece runs through the curve's own points on its range: across the interior knot, starting
// on it, and the whole range; a cubic B-spline too. Ends outside the range are refused.
TEST(CurveOrientation, PieceKeepsTheCurvesPointsOnItsRange) {
  const BSplineCurve c = arc();
  for (const auto& [t0, t1] :
       {std::pair{2.4, 4.1}, {3.0, 5.0}, {2.0, 5.0}, {2.0, 2.7}, {3.5, 3.6}}) {
    const BSplineCurve r = piece(c, t0, t1);
    EXPECT_NO_THROW(r.validate());
    EXPECT_EQ(r.first(), t0);
    EXPECT_EQ(r.last(), t1);
    EXPECT_TRUE(r.rational());
    for (int k = 0; k <= 40; ++k) {
      const double t = t0 + (t1 - t0) * k / 40.0;
      EXPECT_LT((r.evaluate(t) - c.evaluate(t)).norm(), 1e-12) << t0 << " " << t1 << " " << t;
    }
  }
  BSplineCurve cubic;
  cubic.degree = 3;
  cubic.knots = {0, 0, 0, 0, 0.25, 0.5, 0.5, 0.75, 1, 1, 1, 1};
  cubic.poles.resize(8, 2);
  cubic.poles << 0, 0, 1, 2, 2, -1, 3, 3, 4, 0, 5, 1, 6, -2, 7, 0;
  const BSplineCurve r = piece(cubic, 0.1, 0.5);
  EXPECT_FALSE(r.rational());
  EXPECT_EQ(r.pole_count() + 4, static_cast<int>(r.knots.size()));
  for (int k = 0; k <= 40; ++k) {
    const double t = 0.1 + 0.4 * k / 40.0;
    EXPECT_LT((r.evaluate(t) - cubic.evaluate(t)).norm(), 1e-12) << t;
  }
  EXPECT_THROW(piece(c, 1.9, 3.0), InvalidInput);
  EXPECT_THROW(piece(c, 3.0, 3.0), InvalidInput);
  EXPECT_THROW(piece(c, 3.0, 5.1), InvalidInput);
}
