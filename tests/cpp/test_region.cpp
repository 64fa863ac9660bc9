// SPDX-License-Identifier: LGPL-2.1-or-later
// Regions given as closed (u, v) loops: exact quadrature, validation, the poles they touch, and
// operators acting on them.
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/region.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

namespace {

using Loop = std::vector<Eigen::Vector2d>;

Loop rectangle_loop(double u0, double u1, double v0, double v1) {
  return {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}};
}

// sum over the quadrature of f(u, v) * b_i(u, v) * b_j(u, v): a mass matrix entry.
double mass(const SplineSpace& sp, const Region& r, int i, int j) {
  double sum = 0.0;
  for (const QuadraturePoint& q : region_quadrature(sp, r)) {
    const BasisSample s = sp.basis(q.u, q.v, 0);
    double bi = 0.0, bj = 0.0;
    for (size_t k = 0; k < s.index.size(); ++k) {
      if (s.index[k] == i) bi = s.values(0, static_cast<Eigen::Index>(k));
      if (s.index[k] == j) bj = s.values(0, static_cast<Eigen::Index>(k));
    }
    sum += q.weight * bi * bj;
  }
  return sum;
}

double integrate(const SplineSpace& sp, const Region& r, double (*f)(double, double)) {
  double sum = 0.0;
  for (const QuadraturePoint& q : region_quadrature(sp, r)) sum += q.weight * f(q.u, q.v);
  return sum;
}

}  // namespace

TEST(RegionQuadrature, LoopAreaIsExactForANonConvexPolygon) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 7, 5);
  // An arrow-shaped (concave) loop, clockwise, crossing many spans: shoelace area 0.2225.
  Loop arrow = {{0.1, 0.1}, {0.5, 0.45}, {0.9, 0.1}, {0.5, 0.9}};
  std::reverse(arrow.begin(), arrow.end());
  const double shoelace = 0.5 * std::abs((0.1 * 0.45 - 0.5 * 0.1) + (0.5 * 0.1 - 0.9 * 0.45) +
                                         (0.9 * 0.9 - 0.5 * 0.1) + (0.5 * 0.1 - 0.1 * 0.9));
  EXPECT_NEAR(integrate(sp, Region(arrow), [](double, double) { return 1.0; }), shoelace, 1e-14);
}

TEST(RegionQuadrature, TriangleMomentsMatchTheBetaFunction) {
  // Integral over the unit triangle of u^a v^b is a! b! / (a + b + 2)!; degree 6 is within what
  // a bicubic space's rule integrates exactly.
  const SplineSpace sp = SplineSpace::uniform(3, 3, 1, 1);
  const Region tri(Loop{{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}});
  EXPECT_NEAR(integrate(sp, tri, [](double u, double v) { return u * u * u * v * v * v; }),
              36.0 / 40320.0, 1e-16);
  EXPECT_NEAR(integrate(sp, tri, [](double u, double v) { return u * u * v * v * v * v; }),
              2.0 * 24.0 / 40320.0, 1e-16);
}

TEST(RegionQuadrature, RectangleLoopAndLShapeAgreeWithRectangles) {
  const SplineSpace sp = SplineSpace::uniform(3, 2, 6, 5);
  const Region rect(0.13, 0.71, 0.22, 0.93);
  const Region loop(rectangle_loop(0.13, 0.71, 0.22, 0.93));
  // An L made of two rectangles sharing the cut u = 0.5.
  const Region l_shape(
      Loop{{0.13, 0.22}, {0.71, 0.22}, {0.71, 0.5}, {0.5, 0.5}, {0.5, 0.93}, {0.13, 0.93}});
  const Region part_a(0.13, 0.5, 0.22, 0.93), part_b(0.5, 0.71, 0.22, 0.5);
  for (int i : {0, 9, 14, 20, 27})
    for (int j : {0, 9, 14, 20, 27}) {
      EXPECT_NEAR(mass(sp, loop, i, j), mass(sp, rect, i, j), 1e-15) << i << " " << j;
      EXPECT_NEAR(mass(sp, l_shape, i, j), mass(sp, part_a, i, j) + mass(sp, part_b, i, j), 1e-15)
          << i << " " << j;
    }
}

TEST(RegionQuadrature, RejectsBadLoops) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 4, 4);
  auto bad = [&](const Loop& loop) { check_region(sp, Region(loop), "test"); };
  EXPECT_THROW(bad({{0.1, 0.1}, {0.9, 0.9}, {0.9, 0.1}, {0.1, 0.9}}), InvalidInput);  // bow tie
  EXPECT_THROW(bad({{0.1, 0.1}, {1.5, 0.1}, {0.5, 0.9}}), InvalidInput);              // outside
  EXPECT_THROW(bad({{0.1, 0.1}, {0.9, 0.9}}), InvalidInput);                          // no area
  EXPECT_THROW(bad({{0.1, 0.1}, {0.5, 0.5}, {0.9, 0.9}}), InvalidInput);              // collinear
  EXPECT_THROW(bad({{0.1, 0.1}, {NAN, 0.5}, {0.9, 0.1}}), InvalidInput);
  EXPECT_THROW(bad(Loop(static_cast<size_t>(max_loop_points + 1), Eigen::Vector2d(0.5, 0.5))),
               InvalidInput);
  EXPECT_NO_THROW(bad({{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0 + 1e-12}, {0.0, 1.0}}));  // on the edge
}

// A pentagon of straight sides sampled at 48 points each (what exact pre-images of sketch lines
// give): each run is straight up to rounding, a point exactly on a neighbour segment's line and the
// next a rounding off it; that is no crossing. Sides doubling back along themselves still are.
TEST(RegionQuadrature, StraightRunsOfALoopDoNotCrossThemselves) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 4, 4);
  for (double turn : {0.0, 0.1, 0.7, 1.3}) {
    Loop loop;
    for (int side = 0; side < 5; ++side) {
      const double a = turn + 2.0 * M_PI * side / 5, b = turn + 2.0 * M_PI * (side + 1) / 5;
      const Eigen::Vector2d p(0.5 + 0.4 * std::cos(a), 0.5 + 0.4 * std::sin(a));
      const Eigen::Vector2d q(0.5 + 0.4 * std::cos(b), 0.5 + 0.4 * std::sin(b));
      for (int k = 0; k < 48; ++k) loop.push_back(p + (q - p) * (k / 48.0));
    }
    EXPECT_NO_THROW(check_region(sp, Region(loop), "test")) << turn;
  }
  const Loop back = {{0.1, 0.1}, {0.5, 0.1}, {0.9, 0.1}, {0.3, 0.1}, {0.5, 0.8}};
  EXPECT_THROW(check_region(sp, Region(back), "test"), InvalidInput);
}

TEST(RegionQuadrature, PolesOfASmallTriangleInsideOneSpan) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 4, 4);
  // Inside span [0.25, 0.5] x [0.5, 0.75]: the 4 x 4 poles of that span, no more.
  const std::vector<int> poles =
      poles_in_region(sp, Region(Loop{{0.3, 0.55}, {0.45, 0.6}, {0.35, 0.7}}));
  ASSERT_EQ(poles.size(), 16u);
  for (int k : poles) {
    const int i = k / sp.nv(), j = k % sp.nv();
    EXPECT_TRUE(i >= 1 && i <= 4 && j >= 2 && j <= 5) << i << " " << j;
  }
}

TEST(RegionQuadrature, FrozenLoopKeepsTheSurfaceInsideIt) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, 8, 8);
  pb.rest_poles = test::fit_poles(pb.space, [](double u, double v) {
    return Eigen::Vector3d(u, v, 0.1 * std::sin(7 * u) * std::cos(5 * v));
  });
  pb.initial_poles = pb.rest_poles;
  pb.energy = ThinPlateWeights::isotropic(0.1, 1.0);
  pb.fixed_poles = poles_in_region(pb.space, Region(Loop{{0.1, 0.1}, {0.6, 0.2}, {0.3, 0.6}}));
  PointConstraint push;
  push.u = 0.8;
  push.v = 0.8;
  push.target = Eigen::Vector3d(0.8, 0.8, 0.5);
  pb.points.push_back(push);
  const SolveResult r = solve_sheet(pb);
  for (double u : {0.15, 0.3, 0.45})
    for (double v : {0.2, 0.3})
      EXPECT_NEAR((evaluate_surface(pb.space, r.poles, u, v, 0) -
                   evaluate_surface(pb.space, pb.rest_poles, u, v, 0))
                      .norm(),
                  0.0, 1e-12);
  EXPECT_NEAR(evaluate_surface(pb.space, r.poles, 0.8, 0.8, 0)(0, 2), 0.5, 1e-9);
}
