// SPDX-License-Identifier: LGPL-2.1-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

namespace {

// Parameters in (0, 1) where c(t) = a + t (b - a) crosses the interior knot lines of the space.
std::vector<double> line_breaks(const SplineSpace& sp, const Eigen::Vector2d& a,
                                const Eigen::Vector2d& b) {
  std::vector<double> t = {0.0, 1.0};
  const std::vector<double> ku = breakpoints(sp.knots_u, sp.degree_u),
                            kv = breakpoints(sp.knots_v, sp.degree_v);
  for (size_t k = 1; k + 1 < ku.size(); ++k) {
    const double s = (ku[k] - a(0)) / (b(0) - a(0));
    if (s > 0 && s < 1) t.push_back(s);
  }
  for (size_t k = 1; k + 1 < kv.size(); ++k) {
    const double s = (kv[k] - a(1)) / (b(1) - a(1));
    if (s > 0 && s < 1) t.push_back(s);
  }
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end(), [](double x, double y) { return y - x < 1e-12; }),
          t.end());
  return t;
}

SheetProblem problem_with_fixed_boundary(const SplineSpace& sp,
                                         const Eigen::MatrixX3d& boundary_source,
                                         const Eigen::MatrixX3d& initial) {
  SheetProblem pb;
  pb.space = sp;
  pb.initial_poles = initial;
  pb.fixed_poles = boundary_pole_indices(sp);
  for (int k : pb.fixed_poles) pb.initial_poles.row(k) = boundary_source.row(k);
  pb.energy = ThinPlateWeights::isotropic(0.2, 1.0);
  return pb;
}

using test::flat_poles;

// A wavy space curve over the diagonal of the unit square, z within +-0.25: no coarse sheet holds
// it exactly.
CurveConstraint wavy_diagonal_curve() {
  const auto wave = [](double t) {
    const double u = 0.1 + 0.8 * t, v = 0.15 + 0.7 * t;
    return Eigen::VectorXd(Eigen::Vector3d(u, v, 0.2 * std::sin(6 * t) + 0.05 * std::cos(11 * t)));
  };
  std::vector<double> fine;
  for (int i = 0; i <= 64; ++i) fine.push_back(i / 64.0);
  CurveConstraint c;
  c.target = test::fit_piecewise_curve(fine, 5, 3, wave);
  c.preimage = test::line_curve(Eigen::Vector2d(0.1, 0.15), Eigen::Vector2d(0.9, 0.85));
  return c;
}

}  // namespace

TEST(SheetSolver, PlanarSheetWithFixedBoundaryStaysPlanar) {
  SplineSpace sp = SplineSpace::uniform(3, 3, 6, 5);
  sp.knots_u = uniform_clamped_knots(3, 6, 0.0, 2.0);
  const auto plane = [](double u, double v) {
    return Eigen::Vector3d(40 * u, 30 * v + 5 * u, 3 * u - 7 * v + 1);
  };
  const Eigen::MatrixX3d on_plane = test::fit_poles(sp, plane);
  // Start the interior far off the plane: the energy alone must bring it back.
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 10.0);
  Eigen::MatrixX3d start = on_plane;
  for (int k = 0; k < sp.size(); ++k)
    start.row(k) += Eigen::RowVector3d(noise(rng), noise(rng), noise(rng));
  const SolveResult r = solve_sheet(problem_with_fixed_boundary(sp, on_plane, start));
  const Eigen::Vector3d normal =
      Eigen::Vector3d(40, 5, 3).cross(Eigen::Vector3d(0, 30, -7)).normalized();
  for (int k = 0; k < sp.size(); ++k)
    EXPECT_NEAR(normal.dot(r.poles.row(k).transpose() - plane(0, 0)), 0.0, 1e-10) << "pole " << k;
  // Thin plate with a fixed affine boundary: the affine map itself is the minimizer.
  EXPECT_LT((r.poles - on_plane).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(SheetSolver, MembraneBetweenTwoFixedEdgesIsLinear) {
  // Stretch only, w = 0 on u = 0 and w = 1 on u = 1, free elsewhere: the harmonic solution with
  // natural conditions on the free edges is w = u (checked on x and z; y = v is held only on the
  // two fixed edges, and is not harmonic with free-edge conditions, so it is left out).
  const SplineSpace sp = SplineSpace::uniform(3, 3, 5, 4);
  SheetProblem pb;
  pb.space = sp;
  pb.energy = ThinPlateWeights::isotropic(1.0, 0.0);
  const Eigen::MatrixX3d exact =
      test::fit_poles(sp, [](double u, double v) { return Eigen::Vector3d(u, v, u); });
  pb.initial_poles = Eigen::MatrixX3d::Zero(sp.size(), 3);
  for (int j = 0; j < sp.nv(); ++j)
    for (int i : {0, sp.nu() - 1}) {
      pb.fixed_poles.push_back(sp.index(i, j));
      pb.initial_poles.row(sp.index(i, j)) = exact.row(sp.index(i, j));
    }
  const SolveResult r = solve_sheet(pb);
  EXPECT_LT((r.poles.col(0) - exact.col(0)).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_LT((r.poles.col(2) - exact.col(2)).cwiseAbs().maxCoeff(), 1e-10);
  // The free y rows relax away from the straight grid: the solve really did something there.
  EXPECT_GT((r.poles.col(1) - exact.col(1)).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(SheetSolver, MembraneWithABilinearBoundaryIsTheBilinearInterpolant) {
  // Stretch only (Laplace's equation) with every boundary pole on a twisted bilinear patch
  // w = a + b u + c v + d u v: that patch is harmonic and lies in the space, so the Galerkin
  // solution is the patch itself, on a non-uniform space too.
  SplineSpace sp = SplineSpace::uniform(3, 3, 6, 5);
  sp.knots_u[5] = 0.21;
  sp.knots_v[6] = 0.47;
  const Eigen::MatrixX3d exact = test::fit_poles(sp, [](double u, double v) {
    return Eigen::Vector3d(10 * u + 2 * v, 8 * v - u, 3 + 2 * u - v + 7 * u * v);
  });
  SheetProblem pb = problem_with_fixed_boundary(sp, exact, flat_poles(sp));
  pb.energy = ThinPlateWeights::isotropic(1.0, 0.0);
  const SolveResult r = solve_sheet(pb);
  EXPECT_LT((r.poles - exact).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_GT((flat_poles(sp) - exact).cwiseAbs().maxCoeff(), 1.0);  // it started elsewhere
}

class RepresentableCurve : public ::testing::TestWithParam<int> {};

TEST_P(RepresentableCurve, IsMetToTenDigits) {
  // The target is the exact image of a non-isoparametric line under a curved surface of the same
  // space: the solve must reproduce it through the pre-image to 1e-10.
  const int degree = GetParam();
  SplineSpace sp = SplineSpace::uniform(degree, degree, 5, 4);
  sp.knots_v[static_cast<size_t>(degree + 1)] = 0.11;
  const Eigen::MatrixX3d ref = test::fit_poles(sp, [](double u, double v) {
    return Eigen::Vector3d(50 * u + v, 40 * v, 6 * std::sin(2 * u + 1) * std::cos(3 * v));
  });
  const Eigen::Vector2d a(0.07, 0.12), b(0.93, 0.81);
  CurveConstraint c;
  c.preimage = test::line_curve(a, b);
  c.target = test::fit_piecewise_curve(line_breaks(sp, a, b), 2 * degree, 3, [&](double t) {
    const Eigen::Vector2d uv = a + t * (b - a);
    return Eigen::VectorXd(evaluate_surface(sp, ref, uv(0), uv(1), 0).row(0).transpose());
  });
  SheetProblem pb = problem_with_fixed_boundary(sp, ref, flat_poles(sp));
  pb.curves.push_back(c);
  const SolveResult r = solve_sheet(pb);
  EXPECT_LT(incidence_error(sp, r.poles, c, 500), 1e-10);
  EXPECT_LT(r.report.constraint_residual, 1e-10);
  EXPECT_LT(r.report.kkt_residual, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Degrees, RepresentableCurve, ::testing::Values(2, 3, 4));

TEST(SheetSolver, NonIsoparametricCurveConvergesUnderRefinement) {
  // A wavy space curve over the diagonal of a flat, boundary-fixed sheet: no coarse sheet holds
  // it, and the incidence error must fall as the spans are refined.
  const CurveConstraint c = wavy_diagonal_curve();
  double previous = 1e300;
  std::vector<double> errors;
  for (int spans : {2, 4, 8, 16, 32}) {
    const SplineSpace sp = SplineSpace::uniform(3, 3, spans, spans);
    const Eigen::MatrixX3d flat = flat_poles(sp);
    SheetProblem pb = problem_with_fixed_boundary(sp, flat, flat);
    pb.curves.push_back(c);
    const double err = incidence_error(sp, solve_sheet(pb).poles, c, 2000);
    errors.push_back(err);
    EXPECT_LT(err, previous) << "spans " << spans;
    previous = err;
  }
  // Piecewise degree-6 traces: the error falls fast once spans resolve the wave.
  EXPECT_LT(errors.back(), 1e-5);
  EXPECT_LT(errors.back(), 1e-3 * errors.front());
}

TEST(SheetSolver, FitToleranceKeepsCoarseSheetsFair) {
  // The same wavy curve on an 8-span sheet: fitting every singular direction meets the curve
  // closely but throws poles far outside the curve's range (|z| <= 0.25); the discrepancy
  // principle stops at the fit tolerance and the sheet stays as calm as the curve.
  const CurveConstraint c = wavy_diagonal_curve();
  const SplineSpace sp = SplineSpace::uniform(3, 3, 8, 8);
  const Eigen::MatrixX3d flat = flat_poles(sp);
  SheetProblem pb = problem_with_fixed_boundary(sp, flat, flat);
  pb.curves.push_back(c);
  SolveOptions exact, fit;
  fit.fit_tolerance = 1e-3;
  const SolveResult all = solve_sheet(pb, exact), some = solve_sheet(pb, fit);
  EXPECT_GT(all.poles.col(2).cwiseAbs().maxCoeff(), 0.9);
  EXPECT_LT(some.poles.col(2).cwiseAbs().maxCoeff(), 0.35);
  EXPECT_LT(some.report.constraint_rank, all.report.constraint_rank);
  EXPECT_LT(incidence_error(sp, some.poles, c, 2000), 3e-3);
}

TEST(SheetSolver, ReportsConflictOfContradictoryConstraints) {
  // Two points at the same (u, v) with heights 1 and 3 (equal weights): no surface meets both,
  // the best leaves each 1 away, and the RMS of that over the cluster's weight 2 is 1.
  const SplineSpace sp = SplineSpace::uniform(3, 3, 4, 4);
  const Eigen::MatrixX3d flat = flat_poles(sp);
  SheetProblem pb = problem_with_fixed_boundary(sp, flat, flat);
  PointConstraint p;
  p.u = p.v = 0.5;
  p.target = Eigen::Vector3d(0.5, 0.5, 1.0);
  pb.points.push_back(p);
  EXPECT_LT(solve_sheet(pb).report.conflict, 1e-12);
  p.target.z() = 3.0;
  pb.points.push_back(p);
  EXPECT_NEAR(solve_sheet(pb).report.conflict, 1.0, 1e-12);
}

TEST(SheetSolver, PointPullGivesSymmetricBump) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 8, 8);
  const Eigen::MatrixX3d flat = flat_poles(sp);
  SheetProblem pb = problem_with_fixed_boundary(sp, flat, flat);
  PointConstraint p;
  p.u = 0.5;
  p.v = 0.5;
  p.target = Eigen::Vector3d(0.5, 0.5, 1.0);
  pb.points.push_back(p);
  const SolveResult r = solve_sheet(pb);
  auto z = [&](double u, double v) { return evaluate_surface(sp, r.poles, u, v, 0)(0, 2); };
  EXPECT_NEAR(z(0.5, 0.5), 1.0, 1e-12);
  for (double u : {0.1, 0.27, 0.4})
    for (double v : {0.2, 0.33, 0.45}) {
      EXPECT_NEAR(z(u, v), z(1 - u, v), 1e-10);
      EXPECT_NEAR(z(u, v), z(v, u), 1e-10);
      EXPECT_LT(z(u, v), 1.0);
      EXPECT_GT(z(u, v), 0.0);
    }
}

TEST(SheetSolver, ContradictoryPointsMeetInWeightedLeastSquares) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 4, 4);
  const Eigen::MatrixX3d flat = flat_poles(sp);
  SheetProblem pb = problem_with_fixed_boundary(sp, flat, flat);
  PointConstraint p;
  p.u = p.v = 0.5;
  p.target = Eigen::Vector3d(0.5, 0.5, 1.0);
  p.weight = 1.0;
  pb.points.push_back(p);
  p.target.z() = 3.0;
  p.weight = 3.0;
  pb.points.push_back(p);
  const SolveResult r = solve_sheet(pb);
  EXPECT_EQ(r.report.constraint_rank, 1);
  EXPECT_NEAR(evaluate_surface(sp, r.poles, 0.5, 0.5, 0)(0, 2), (1.0 * 1.0 + 3.0 * 3.0) / 4.0,
              1e-12);
}

TEST(SheetSolver, UndeterminedDirectionsStayWhereTheyStarted) {
  // Bending only and one point: an affine tilt about the point is free. The solve must not fail,
  // and must keep the initial shape in those directions (the regularization's job) up to the
  // roundoff a 1e-10 shift allows (1e-16 / 1e-10 relative).
  const SplineSpace sp = SplineSpace::uniform(3, 3, 3, 3);
  SheetProblem pb;
  pb.space = sp;
  pb.energy = ThinPlateWeights::isotropic(0.0, 1.0);
  pb.initial_poles = flat_poles(sp);
  PointConstraint p;
  p.u = p.v = 0.5;
  p.target = Eigen::Vector3d(0.5, 0.5, 0.0);
  pb.points.push_back(p);
  const SolveResult r = solve_sheet(pb);
  EXPECT_LT((r.poles - pb.initial_poles).cwiseAbs().maxCoeff(), 1e-4);
  EXPECT_LT((evaluate_surface(sp, r.poles, 0.5, 0.5, 0).row(0).transpose() - p.target).norm(),
            1e-10);
}

TEST(SheetSolver, RejectsBadProblems) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 4, 4);
  SheetProblem pb;
  pb.space = sp;
  pb.initial_poles = flat_poles(sp);
  pb.initial_poles(2, 2) = NAN;
  EXPECT_THROW(solve_sheet(pb), InvalidInput);
  pb.initial_poles = flat_poles(sp);
  pb.fixed_poles = {sp.size()};
  EXPECT_THROW(solve_sheet(pb), InvalidInput);
  pb.fixed_poles.clear();
  SolveOptions opt;
  opt.max_unknowns = 10;
  EXPECT_THROW(solve_sheet(pb, opt), ResourceLimit);
  opt = SolveOptions();
  opt.rank_tolerance = 0.0;
  pb.points.push_back(PointConstraint());
  EXPECT_THROW(solve_sheet(pb, opt), InvalidInput);
  CurveConstraint c;
  c.target = test::line_curve(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0));
  c.preimage = test::line_curve(Eigen::Vector2d(0.2, 0.2), Eigen::Vector2d(1.5, 0.2));
  pb.curves.push_back(c);
  try {
    solve_sheet(pb);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("curve 0"), std::string::npos) << e.what();
  }
}

TEST(SheetSolver, ExactIncidenceMeetsARepresentableCurveWhereTheToleranceFitStops) {
  // The exact image of a diagonal line under a curved sheet of the same space, solved from a flat
  // start with a 0.01 fit tolerance: the tolerance fit stops once it is within 0.01 (RMS), the
  // exact form fits every direction and meets the curve to rounding.
  SplineSpace sp = SplineSpace::uniform(3, 3, 6, 5);
  const Eigen::MatrixX3d ref = test::fit_poles(sp, [](double u, double v) {
    return Eigen::Vector3d(50 * u + v, 40 * v, 6 * std::sin(2 * u + 1) * std::cos(3 * v));
  });
  const Eigen::Vector2d a(0.07, 0.12), b(0.93, 0.81);
  CurveConstraint c;
  c.preimage = test::line_curve(a, b);
  c.target = test::fit_piecewise_curve(line_breaks(sp, a, b), 6, 3, [&](double t) {
    const Eigen::Vector2d uv = a + t * (b - a);
    return Eigen::VectorXd(evaluate_surface(sp, ref, uv(0), uv(1), 0).row(0).transpose());
  });
  SolveOptions opt;
  opt.fit_tolerance = 0.01;
  SheetProblem pb = problem_with_fixed_boundary(sp, ref, flat_poles(sp));
  pb.curves.push_back(c);
  const double fitted = incidence_error(sp, solve_sheet(pb, opt).poles, c, 500);
  pb.curves[0].exact = true;
  const double exact = incidence_error(sp, solve_sheet(pb, opt).poles, c, 500);
  EXPECT_LT(exact, 1e-9);
  EXPECT_GT(fitted, 1e-6);  // it only approached the curve
  EXPECT_LT(fitted, 0.1);   // but it did approach it
}

TEST(SheetSolver, ATrimmedSheetIsTheFairestSheetOfItsKeptRegionAlone) {
  // Sheet A spans [0, 1]^2 but keeps only R = [0.25, 0.75]^2 (a trim); sheet B spans R itself,
  // with the same knot lines. A's splines restricted to R are exactly B's, so with the energy on
  // R only, A's solution over R must be B's: the overhang must not pull on it. Both hold the
  // same four curves along R's edges and a point in the middle.
  auto problem = [](const SplineSpace& sp) {
    SheetProblem pb;
    pb.space = sp;
    pb.initial_poles =
        test::fit_poles(sp, [](double u, double v) { return Eigen::Vector3d(u, v, 0.0); });
    pb.energy = ThinPlateWeights::isotropic(0.1, 1.0);
    const auto height = [](double u, double v) {
      return 0.5 * (u - 0.5) * (u - 0.5) - (v - 0.5) * (v - 0.5) * (v - 0.5);
    };
    const Eigen::Vector2d corner[4] = {{0.25, 0.25}, {0.75, 0.25}, {0.75, 0.75}, {0.25, 0.75}};
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d a = corner[k], b = corner[(k + 1) % 4];
      CurveConstraint c;
      c.preimage = test::line_curve(a, b);
      // Cubic along each edge: exactly representable in both spaces.
      c.target = test::fit_piecewise_curve({0.0, 1.0}, 3, 3, [&](double t) {
        const Eigen::Vector2d q = a + t * (b - a);
        return Eigen::VectorXd(Eigen::Vector3d(q(0), q(1), height(q(0), q(1))));
      });
      pb.curves.push_back(c);
    }
    PointConstraint pin;
    pin.u = pin.v = 0.5;
    pin.target = Eigen::Vector3d(0.5, 0.5, 0.2);
    pb.points.push_back(pin);
    return pb;
  };
  SplineSpace big = SplineSpace::uniform(3, 3, 8, 8);
  SplineSpace small = SplineSpace::uniform(3, 3, 4, 4);
  for (auto& k : small.knots_u) k = 0.25 + 0.5 * k;
  small.knots_v = small.knots_u;
  SolveOptions exact;
  exact.mode = SolveMode::exact;
  const SolveResult reference = solve_sheet(problem(small), exact);
  SheetProblem trimmed = problem(big);
  trimmed.kept_region = Region({{0.25, 0.25}, {0.75, 0.25}, {0.75, 0.75}, {0.25, 0.75}});
  auto largest_difference = [&](const SheetProblem& pb) {
    const SolveResult r = solve_sheet(pb, exact);
    double worst = 0.0;
    for (int i = 0; i <= 20; ++i)
      for (int j = 0; j <= 20; ++j) {
        const double u = 0.25 + 0.025 * i, v = 0.25 + 0.025 * j;
        worst = std::max(worst, (evaluate_surface(big, r.poles, u, v, 0) -
                                 evaluate_surface(small, reference.poles, u, v, 0))
                                    .norm());
      }
    return worst;
  };
  // The overhang's small share of the energy moves the kept part by about that share.
  trimmed.overhang_energy = 1e-8;
  EXPECT_LT(largest_difference(trimmed), 1e-6);
  trimmed.overhang_energy = 1e-4;
  EXPECT_LT(largest_difference(trimmed), 1e-3 * 0.2);
  // The untrimmed energy (the overhang counts in full) gives a visibly different sheet.
  trimmed.kept_region.reset();
  EXPECT_GT(largest_difference(trimmed), 1e-2 * 0.2);
}
