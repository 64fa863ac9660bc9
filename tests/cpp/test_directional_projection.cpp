// SPDX-License-Identifier: LGPL-2.1-or-later
// LineFoot: where the line through a point along a direction meets a sheet. Checked on a wavy
// graph z = f(x, y) whose x and y are exactly u and v, so the foot straight down is known.
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/occ/directional_projection.hpp"

namespace varsurf {
namespace {

// 100 x 80 mm, bicubic with 8 x 8 spans; x = 100 u and y = 80 v exactly (poles at the Greville
// points), z a wave of +-12 mm.
BSplineSurface wavy_graph() {
  BSplineSurface s;
  s.space = SplineSpace::uniform(3, 3, 8, 8);
  const std::vector<double> gu = test::greville(s.space.knots_u, 3);
  const std::vector<double> gv = test::greville(s.space.knots_v, 3);
  s.poles.resize(s.space.size(), 3);
  for (int i = 0; i < s.space.nu(); ++i)
    for (int j = 0; j < s.space.nv(); ++j)
      s.poles.row(s.space.index(i, j)) << 100.0 * gu[i], 80.0 * gv[j],
          12.0 * std::sin(9.0 * gu[i]) * std::cos(7.0 * gv[j]);
  return s;
}

TEST(LineFoot, StraightDownFindsThePointBelow) {
  const BSplineSurface s = wavy_graph();
  const occ::LineFoot foot(s, Eigen::Vector3d(0.0, 0.0, -3.0));
  Eigen::Vector2d previous;
  for (int k = 0; k <= 40; ++k) {
    const double x = 5.0 + 2.2 * k, y = 10.0 + 1.5 * k;
    const Eigen::Vector3d p(x, y, 30.0);  // 18 to 42 mm above the wave
    const Eigen::Vector2d uv = foot(p, k == 0 ? nullptr : &previous);
    EXPECT_NEAR(uv(0), x / 100.0, 1e-12);
    EXPECT_NEAR(uv(1), y / 80.0, 1e-12);
    previous = uv;
  }
}

TEST(LineFoot, ObliqueDirectionMeetsTheSheetOnTheLine) {
  const BSplineSurface s = wavy_graph();
  const Eigen::Vector3d d = Eigen::Vector3d(0.3, -0.2, -1.0).normalized();
  const occ::LineFoot foot(s, d);
  for (int k = 0; k <= 10; ++k) {
    const Eigen::Vector3d p(30.0 + 4.0 * k, 30.0 + 2.0 * k, 25.0);
    const Eigen::Vector2d uv = foot(p, nullptr);
    const Eigen::Vector3d q = s.evaluate(uv(0), uv(1));
    // q lies on the line through p along d: no component across it.
    EXPECT_LT((q - p).cross(d).norm(), 1e-9);
    // Independently: f(x(s), y(s)) = z(s) along the line, solved by bisection.
    double lo = 0.0, hi = 80.0;
    auto gap = [&](double t) {
      const Eigen::Vector3d r = p + t * d;
      return r(2) - s.evaluate(r(0) / 100.0, r(1) / 80.0)(2);
    };
    for (int it = 0; it < 200; ++it) (gap(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
    const Eigen::Vector3d r = p + lo * d;
    EXPECT_NEAR(uv(0), r(0) / 100.0, 1e-10);
    EXPECT_NEAR(uv(1), r(1) / 80.0, 1e-10);
  }
}

TEST(LineFoot, PointBeyondTheFaceInThisViewThrows) {
  const BSplineSurface s = wavy_graph();
  const occ::LineFoot foot(s, Eigen::Vector3d::UnitZ());
  EXPECT_THROW(foot(Eigen::Vector3d(120.0, 40.0, 30.0), nullptr), InvalidInput);
  const Eigen::Vector2d inside = foot(Eigen::Vector3d(99.0, 40.0, 30.0), nullptr);
  EXPECT_THROW(foot(Eigen::Vector3d(101.0, 40.0, 30.0), &inside), InvalidInput);
}

TEST(LineFoot, GrazingAndBadDirectionsThrow) {
  const BSplineSurface s = wavy_graph();
  EXPECT_THROW(occ::LineFoot(s, Eigen::Vector3d::Zero()), InvalidInput);
  EXPECT_THROW(occ::LineFoot(s, Eigen::Vector3d(NAN, 0.0, 1.0)), InvalidInput);
  // Flat sheet seen edge-on: every line along x lies in or misses the plane.
  BSplineSurface flat;
  flat.space = SplineSpace::uniform(3, 3, 2, 2);
  flat.poles = test::flat_poles(flat.space) * 50.0;
  const occ::LineFoot edge_on(flat, Eigen::Vector3d(1.0, 0.0, 0.01));
  EXPECT_THROW(edge_on(Eigen::Vector3d(-10.0, 25.0, 0.05), nullptr), InvalidInput);
}

}  // namespace
}  // namespace varsurf
