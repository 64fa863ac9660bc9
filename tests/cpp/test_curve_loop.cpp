// SPDX-License-Identifier: LGPL-2.1-or-later
// 2D curves chained into a closed loop, in any order and direction.
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "varsurf/core/curve_loop.hpp"
#include "varsurf/core/errors.hpp"

using namespace varsurf;

namespace {

BSplineCurve line(double x0, double y0, double x1, double y1) {
  return test::line_curve(Eigen::Vector2d(x0, y0), Eigen::Vector2d(x1, y1));
}

}  // namespace

TEST(CurveLoop, ShuffledAndReversedSidesOfASquare) {
  // The unit square's sides, out of order, two of them walked backwards.
  const std::vector<BSplineCurve> sides = {line(0, 0, 1, 0), line(0, 1, 1, 1), line(1, 0, 1, 1),
                                           line(0, 0, 0, 1)};
  const CurveLoop loop = chain_loop(sides, 1e-9);
  ASSERT_EQ(loop.steps.size(), 4u);
  const std::vector<int> order = {0, 2, 1, 3};
  const std::vector<bool> reversed = {false, false, true, true};
  // The square lies left of the bottom (+x) and right sides (+y), right of the top (+x) and left.
  const std::vector<int> inside = {1, 1, -1, -1};
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(loop.steps[i].curve, order[i]);
    EXPECT_EQ(loop.steps[i].reversed, reversed[i]);
    EXPECT_EQ(loop.steps[i].inside, inside[i]);
  }
  EXPECT_NEAR(loop.signed_area, 1.0, 1e-12);  // counter-clockwise
  // Walked the other way round the area changes sign.
  const std::vector<BSplineCurve> clockwise = {line(0, 0, 0, 1), line(0, 1, 1, 1)};
  EXPECT_THROW(chain_loop(clockwise, 1e-9), InvalidInput);  // open: two sides only
  const CurveLoop cw =
      chain_loop({line(0, 0, 0, 1), line(0, 1, 1, 1), line(1, 1, 1, 0), line(1, 0, 0, 0)}, 1e-9);
  EXPECT_NEAR(cw.signed_area, -1.0, 1e-12);
  for (const LoopStep& step : cw.steps) EXPECT_EQ(step.inside, -1);  // walked clockwise, forward
}

TEST(CurveLoop, GapsAndBadCurves) {
  EXPECT_THROW(chain_loop({}, 1e-9), InvalidInput);
  EXPECT_THROW(chain_loop({line(0, 0, 1, 0), line(1, 1e-6, 0, 0)}, 1e-9), InvalidInput);
  EXPECT_NO_THROW(chain_loop({line(0, 0, 1, 0), line(1, 1e-12, 0, 0)}, 1e-9));
  EXPECT_THROW(
      chain_loop({test::line_curve(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0))}, 1e-9),
      InvalidInput);
}
