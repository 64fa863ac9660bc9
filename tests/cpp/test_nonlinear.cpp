// Repellers and pressure: the energy terms that are not quadratic in the poles.
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
