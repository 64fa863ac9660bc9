// SPDX-License-Identifier: LGPL-2.1-or-later
// Repellers, shape attractors and pressure: the energy terms that are not quadratic in the poles.
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

namespace {

SheetProblem flat_problem(int spans, double stretch, double bend) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, spans, spans);
  pb.initial_poles =
      test::fit_poles(pb.space, [](double u, double v) { return Eigen::Vector3d(u, v, 0.0); });
  pb.fixed_poles = boundary_pole_indices(pb.space);
  pb.energy = ThinPlateWeights::isotropic(stretch, bend);
  return pb;
}

double height(const SheetProblem& pb, const Eigen::MatrixX3d& poles, double u, double v) {
  return evaluate_surface(pb.space, poles, u, v, 0)(0, 2);
}

}  // namespace

TEST(Pressure, SmallInflationOfAMembraneMatchesThePoissonSolution) {
  // Energy alpha |grad w|^2 (no 1/2) minus the work P V: -2 alpha Laplace(w) = P with w = 0 on the
  // unit square's boundary, whose centre value is 0.0736713 P / (2 alpha) (series solution).
  SheetProblem pb = flat_problem(16, 1.0, 0.0);
  pb.pressure = 1e-3;
  const SolveResult r = solve_sheet(pb);
  EXPECT_TRUE(r.report.converged);
  EXPECT_GE(r.report.iterations, 1);
  const double exact = 0.0736713 * pb.pressure / 2.0;
  EXPECT_NEAR(height(pb, r.poles, 0.5, 0.5), exact, 0.01 * exact);
  // Deflation is the mirror image.
  pb.pressure = -1e-3;
  EXPECT_NEAR(height(pb, solve_sheet(pb).poles, 0.5, 0.5), -exact, 0.01 * exact);
}

TEST(Pressure, LargeInflationFollowsTheNormalAndConverges) {
  // With a large pressure the iterated solve (normals updated, steps limited) must converge. The
  // pressure follows the tilting normals and the bending term stiffens the sheet, so the bulge
  // stays below the linear membrane answer 0.0736713 P / (2 alpha), but well above half of it.
  SheetProblem pb = flat_problem(12, 1.0, 0.01);
  pb.pressure = 2.0;
  const SolveResult r = solve_sheet(pb);
  EXPECT_TRUE(r.report.converged) << r.report.iterations << " steps, last " << r.report.last_step;
  const double linear = 0.0736713 * pb.pressure / 2.0;
  EXPECT_LT(height(pb, r.poles, 0.5, 0.5), linear);
  EXPECT_GT(height(pb, r.poles, 0.5, 0.5), 0.5 * linear);
  EXPECT_LT(r.report.last_step, 1e-8);
}

TEST(Repeller, PushesTheSheetAwayMoreWithStrengthAndConverges) {
  double previous = 0.0;
  for (double strength : {1e-4, 1e-3, 1e-2}) {
    SheetProblem pb = flat_problem(10, 0.1, 1.0);
    Repeller rep;
    rep.region = Region{0.3, 0.7, 0.3, 0.7};
    rep.origin = Eigen::Vector3d(0.5, 0.5, 0.1);
    rep.strength = strength;
    pb.repellers.push_back(rep);
    const SolveResult r = solve_sheet(pb);
    EXPECT_TRUE(r.report.converged) << strength;
    const double distance = 0.1 - height(pb, r.poles, 0.5, 0.5);  // the sheet moves down, away
    EXPECT_GT(distance, previous) << strength;
    previous = distance;
  }
  EXPECT_GT(previous, 0.11);
}

TEST(Repeller, KeepsTheConstraints) {
  SheetProblem pb = flat_problem(10, 0.1, 1.0);
  PointConstraint p;
  p.u = 0.5;
  p.v = 0.5;
  p.target = Eigen::Vector3d(0.5, 0.5, 0.0);
  pb.points.push_back(p);
  Repeller rep;
  rep.region = Region{0.3, 0.7, 0.3, 0.7};
  rep.origin = Eigen::Vector3d(0.5, 0.5, 0.05);
  rep.strength = 1e-2;
  pb.repellers.push_back(rep);
  const SolveResult r = solve_sheet(pb);
  EXPECT_TRUE(r.report.converged);
  EXPECT_NEAR(height(pb, r.poles, 0.5, 0.5), 0.0, 1e-10);
  EXPECT_LT(height(pb, r.poles, 0.4, 0.5), -1e-3);  // around the pinned point it is pushed away
  rep.strength = NAN;
  pb.repellers = {rep};
  EXPECT_THROW(solve_sheet(pb), InvalidInput);
}

namespace {

// Closest points of the plane through `origin` with normal n, and its Gauss-Newton metric.
ClosestPointFunction plane_target(const Eigen::Vector3d& origin, const Eigen::Vector3d& normal) {
  const Eigen::Vector3d n = normal.normalized();
  return [origin, n](const Eigen::Vector3d& p) {
    ClosestPoint c;
    c.point = p - n.dot(p - origin) * n;
    c.metric = n * n.transpose();
    return c;
  };
}

ClosestPointFunction sphere_target(const Eigen::Vector3d& centre, double radius) {
  return [centre, radius](const Eigen::Vector3d& p) {
    const Eigen::Vector3d n = (p - centre).normalized();
    ClosestPoint c;
    c.point = centre + radius * n;
    c.metric = n * n.transpose();
    return c;
  };
}

}  // namespace

TEST(ShapeAttractor, OnAPlaneEqualsThePlaneAttractor) {
  // dist(w, plane)^2 is exactly the plane attractor's energy: both solves must agree.
  const Eigen::Vector3d origin(0.5, 0.5, 0.3), normal(0.0, 0.3, 1.0);
  for (const Region& region :
       {Region(0.3, 0.7, 0.4, 0.6), Region({{0.2, 0.2}, {0.8, 0.3}, {0.5, 0.8}})}) {
    SheetProblem with_plane = flat_problem(8, 0.1, 1.0);
    Attractor a;
    a.kind = AttractorKind::plane;
    a.region = region;
    a.origin = origin;
    a.direction = normal;
    a.strength = 10.0;
    with_plane.attractors.push_back(a);
    SheetProblem with_shape = flat_problem(8, 0.1, 1.0);
    with_shape.shape_attractors.push_back({region, plane_target(origin, normal), 10.0});
    const SolveResult expected = solve_sheet(with_plane);
    const SolveResult got = solve_sheet(with_shape);
    EXPECT_TRUE(got.report.converged);
    EXPECT_LT((got.poles - expected.poles).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST(ShapeAttractor, PullsTheRegionOntoASphereMoreWithStrengthAndConverges) {
  const Eigen::Vector3d centre(0.5, 0.5, -0.7);
  const double radius = 1.0;  // its top, z = 0.3, lies above the flat sheet
  double previous = 1e300;
  for (double strength : {0.1, 1.0, 10.0, 1e3}) {
    SheetProblem pb = flat_problem(12, 0.1, 1.0);
    pb.shape_attractors.push_back(
        {Region(0.3, 0.7, 0.3, 0.7), sphere_target(centre, radius), strength});
    const SolveResult r = solve_sheet(pb);
    EXPECT_TRUE(r.report.converged) << strength;
    // The penalized term, the integral of dist^2 over the region, cannot grow with strength.
    double sum = 0.0;
    for (int i = 0; i <= 20; ++i)
      for (int j = 0; j <= 20; ++j) {
        const Eigen::Vector3d w =
            evaluate_surface(pb.space, r.poles, 0.3 + 0.02 * i, 0.3 + 0.02 * j, 0)
                .row(0)
                .transpose();
        sum += std::pow((w - centre).norm() - radius, 2);
      }
    const double gap = std::sqrt(sum / 441.0);
    EXPECT_LT(gap, previous) << strength << " iterations " << r.report.iterations;
    previous = gap;
  }
  EXPECT_LT(previous, 2e-4);  // RMS, from about 0.28 with no pull
}

TEST(ShapeAttractor, RejectsMissingTargetsAndBadAnswers) {
  SheetProblem pb = flat_problem(4, 0.1, 1.0);
  pb.shape_attractors.push_back({Region(0.3, 0.7, 0.3, 0.7), nullptr, 1.0});
  EXPECT_THROW(solve_sheet(pb), InvalidInput);
  pb.shape_attractors[0].closest = [](const Eigen::Vector3d&) {
    ClosestPoint c;
    c.point = Eigen::Vector3d::Constant(NAN);
    return c;
  };
  EXPECT_THROW(solve_sheet(pb), InvalidInput);
}
