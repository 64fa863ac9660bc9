// SPDX-License-Identifier: LGPL-2.1-or-later
// The discrepancy principle with a rest shape: constraints the rest shape already meets within
// the fit tolerance leave the sheet alone in every solve mode; a sheet with nothing to do stays
// exactly on its rest shape at every degree; the penalty mode survives a semi-definite system.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "test_support.hpp"
#include "varsurf/core/external_energy.hpp"
#include "varsurf/core/sheet_solver.hpp"
#include "varsurf/core/thin_plate_energy.hpp"

using namespace varsurf;

namespace {

const SolveMode kAllModes[] = {SolveMode::exact, SolveMode::penalty, SolveMode::cg,
                               SolveMode::tsvd,  SolveMode::mtsvd,   SolveMode::automatic};

Eigen::Vector3d wavy(double u, double v) {
  return {u, v, 0.2 * std::sin(2.0 * u + 0.3) * std::cos(1.7 * v) + 0.1 * u * v};
}

// A wavy unit sheet (not representable exactly: its poles are an interpolant) that is its own
// rest shape, boundary held.
SheetProblem rest_problem(int degree, int spans, bool fix_boundary = true) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(degree, degree, spans, spans);
  pb.rest_poles = test::fit_poles(pb.space, wavy);
  pb.initial_poles = pb.rest_poles;
  if (fix_boundary) pb.fixed_poles = boundary_pole_indices(pb.space);
  pb.energy = ThinPlateWeights::isotropic(0.1, 1.0);
  return pb;
}

// The sheet's own image of the line (u0, v0) -> (u1, v1), lifted by `lift` along z and with
// `noise` of amplitude added (a fast wave along z): a curve lying within |lift| + noise of it.
CurveConstraint curve_on(const SheetProblem& pb, Eigen::Vector2d a, Eigen::Vector2d b, double lift,
                         double noise) {
  CurveConstraint c;
  c.preimage = test::line_curve(a, b);
  std::vector<double> breaks;
  for (int i = 0; i <= 24; ++i) breaks.push_back(i / 24.0);
  c.target = test::fit_piecewise_curve(breaks, 5, 3, [&](double t) {
    const Eigen::Vector2d uv = a + t * (b - a);
    Eigen::Vector3d p = evaluate_surface(pb.space, pb.rest_poles, uv(0), uv(1), 0).transpose();
    p(2) += lift + noise * std::sin(41.0 * t + 0.5);
    return Eigen::VectorXd(p);
  });
  return c;
}

// Largest distance between two sheets of one space, on a 41 x 41 parameter grid.
double sheet_gap(const SplineSpace& space, const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) {
  double gap = 0.0;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) {
      const double u = i / 40.0, v = j / 40.0;
      gap = std::max(
          gap, (evaluate_surface(space, a, u, v, 0) - evaluate_surface(space, b, u, v, 0)).norm());
    }
  return gap;
}

class HeldNoise : public ::testing::TestWithParam<SolveMode> {};

// Curves within a fraction of the fit tolerance of the rest shape (noise along them, as a curve
// drawn on a face and read back carries) leave the sheet on its rest shape. Before, every mode
// fitted the noise: bumps of 10-100x its amplitude, hundreds of times it in TSVD.
TEST_P(HeldNoise, CurvesTheRestShapeMeetsLeaveTheSheetAlone) {
  SheetProblem pb = rest_problem(3, 16);
  const double fit = 1e-3, noise = 0.3 * fit;
  pb.curves.push_back(curve_on(pb, {0.1, 0.2}, {0.9, 0.7}, 0.0, noise));
  pb.curves.push_back(curve_on(pb, {0.15, 0.85}, {0.8, 0.15}, 0.0, noise));
  SolveOptions opt;
  opt.mode = GetParam();
  opt.fit_tolerance = fit;
  opt.cluster_limit = 20;  // Automatic: large enough groups go to the penalty mode
  const SolveResult r = solve_sheet(pb, opt);
  ASSERT_TRUE(r.poles.allFinite());
  EXPECT_LT(sheet_gap(pb.space, r.poles, pb.rest_poles), 1e-12) << r.report.mode_reason;
  if (GetParam() == SolveMode::tsvd || GetParam() == SolveMode::mtsvd)
    EXPECT_EQ(r.report.constraint_rank, 0);  // the L-curve modes fit no direction
  else
    EXPECT_GT(r.report.held_constraints, 0) << r.report.mode_reason;
  for (const CurveConstraint& c : pb.curves)
    EXPECT_LT(test::curve_gap(pb, r.poles, c), 1.01 * noise);
}

INSTANTIATE_TEST_SUITE_P(Modes, HeldNoise, ::testing::ValuesIn(kAllModes),
                         [](const auto& info) { return std::string(to_string(info.param)); });

// A curve the rest shape does not meet is fitted to the tolerance; a held one next to it keeps
// the sheet where it is (within the tolerance) although the fit pulls on the sheet around it.
TEST(Discrepancy, FittedCurveNextToAHeldOne) {
  for (SolveMode mode : {SolveMode::exact, SolveMode::penalty, SolveMode::cg}) {
    SheetProblem pb = rest_problem(3, 16);
    const double fit = 1e-3;
    pb.curves.push_back(curve_on(pb, {0.2, 0.3}, {0.8, 0.35}, 0.02, 0.0));       // lifted: fitted
    pb.curves.push_back(curve_on(pb, {0.2, 0.6}, {0.8, 0.65}, 0.0, 0.3 * fit));  // noise: held
    SolveOptions opt;
    opt.mode = mode;
    opt.fit_tolerance = fit;
    const SolveResult r = solve_sheet(pb, opt);
    SCOPED_TRACE(to_string(mode));
    EXPECT_LT(test::curve_gap(pb, r.poles, pb.curves[0]), 4.0 * fit);
    EXPECT_LT(test::curve_gap(pb, r.poles, pb.curves[1]), 4.0 * fit);
    EXPECT_GT(sheet_gap(pb.space, r.poles, pb.rest_poles), 0.015);  // the lift was taken
  }
}

// A held curve still follows its own motion: dragged off the rest shape, the sheet goes with it.
TEST(Discrepancy, HeldCurveDraggedMovesTheSheet) {
  for (SolveMode mode : {SolveMode::exact, SolveMode::penalty}) {
    SheetProblem pb = rest_problem(3, 12);
    const double fit = 1e-3;
    pb.curves.push_back(curve_on(pb, {0.2, 0.4}, {0.8, 0.6}, 0.0, 0.3 * fit));
    SolveOptions opt;
    opt.mode = mode;
    opt.fit_tolerance = fit;
    PreparedSheet prepared(pb, opt);
    EXPECT_LT(sheet_gap(pb.space, prepared.result().poles, pb.rest_poles), 1e-12);
    SheetProblem moved = pb;
    moved.curves[0].target.poles.col(2).array() += 0.05;
    const SolveResult r = prepared.update(moved);
    SCOPED_TRACE(to_string(mode));
    EXPECT_LT(test::curve_gap(moved, r.poles, moved.curves[0]), 4.0 * fit);
    EXPECT_GT(sheet_gap(pb.space, r.poles, pb.rest_poles), 0.04);
  }
}

// Operators on a sheet with a rest shape: the energy is (p - rest)^T H (p - rest) plus the
// operators' own quadratic terms, not centred on the rest shape. Checked by the optimality
// condition assembled here from the public pieces: H (p - rest) + A p = f on every free pole.
TEST(RestShape, OperatorsAreNotCentredOnTheRestShape) {
  SheetProblem pb = rest_problem(3, 10);
  Attractor a;
  a.kind = AttractorKind::point;
  a.region = Region{0.3, 0.7, 0.3, 0.6};
  a.origin = Eigen::Vector3d(0.5, 0.45, 0.6);
  a.strength = 0.5;
  pb.attractors.push_back(a);
  const SolveResult r = solve_sheet(pb, {});
  ASSERT_FALSE(r.report.coupled);
  const Eigen::SparseMatrix<double> h = assemble_thin_plate(pb.space, pb.energy);
  QuadraticTerms terms(pb.space.size());
  add_attractor(pb.space, a, operator_scales(pb.space, h).value, terms);
  Eigen::SparseMatrix<double> extra(pb.space.size(), pb.space.size());
  extra.setFromTriplets(terms.separable.begin(), terms.separable.end());
  const Eigen::MatrixX3d gradient =
      h * (r.poles - pb.rest_poles) + extra * r.poles - terms.separable_f;
  std::vector<bool> fixed(static_cast<size_t>(pb.space.size()), false);
  for (int k : pb.fixed_poles) fixed[static_cast<size_t>(k)] = true;
  const double scale = (extra * r.poles).cwiseAbs().maxCoeff();
  for (int k = 0; k < pb.space.size(); ++k)
    if (!fixed[static_cast<size_t>(k)]) {
      EXPECT_LT(gradient.row(k).cwiseAbs().maxCoeff(), 1e-9 * scale) << "pole " << k;
    }
  EXPECT_GT(sheet_gap(pb.space, r.poles, pb.rest_poles), 0.05);  // the attractor pulled
}

class RestAtDegree : public ::testing::TestWithParam<int> {};

// With nothing asking it to move, a sheet is its rest shape at every degree, boundary held or
// free. Before, the solve recovered the poles as Q^-1 (Q rest): the energy's conditioning at
// degrees 5-7 (and its null space with a free boundary) let them drift by 1e-5 of the size.
TEST_P(RestAtDegree, NoConstraintsNoMotion) {
  for (bool fixed : {true, false})
    for (SolveMode mode : kAllModes) {
      const SheetProblem pb = rest_problem(GetParam(), 12, fixed);
      SolveOptions opt;
      opt.mode = mode;
      opt.fit_tolerance = 1e-3;
      const SolveResult r = solve_sheet(pb, opt);
      SCOPED_TRACE(std::string(to_string(mode)) + (fixed ? " fixed" : " free"));
      EXPECT_LT(sheet_gap(pb.space, r.poles, pb.rest_poles), 1e-12);
    }
}

INSTANTIATE_TEST_SUITE_P(Degrees, RestAtDegree, ::testing::Range(2, 8));

// A penalty system that is only semi-definite (bending alone leaves the affine motions free, no
// pole held, no regularization): the mode regularizes it, says so, and returns finite poles
// that meet the curve, as the exact mode does; Automatic does the same when it picks the penalty
// mode. Before, the factorization of a singular matrix was used as it came.
TEST(PenaltyMode, SemiDefiniteSystemIsRegularized) {
  SheetProblem pb = rest_problem(6, 14, /*fix_boundary=*/false);
  pb.curves.push_back(curve_on(pb, {0.1, 0.5}, {0.9, 0.5}, 0.05, 0.0));
  pb.rest_poles.resize(0, 3);
  pb.energy = ThinPlateWeights::isotropic(0.0, 1.0);
  SolveOptions exact;
  exact.mode = SolveMode::exact;
  const SolveResult reference = solve_sheet(pb, exact);
  const Eigen::SparseMatrix<double> h = assemble_thin_plate(pb.space, pb.energy);
  for (SolveMode mode : {SolveMode::penalty, SolveMode::automatic}) {
    SolveOptions opt;
    opt.mode = mode;
    opt.fit_tolerance = 1e-5;
    opt.regularization = 0.0;
    opt.cluster_limit = 20;
    const SolveResult r = solve_sheet(pb, opt);
    SCOPED_TRACE(to_string(mode));
    EXPECT_EQ(r.report.mode, SolveMode::penalty);
    EXPECT_NE(r.report.mode_reason.find("not positive definite"), std::string::npos)
        << r.report.mode_reason;
    ASSERT_TRUE(r.poles.allFinite());
    EXPECT_LT(test::curve_gap(pb, r.poles, pb.curves[0]), 4e-5);
    // Meeting the curve only within the tolerance, the sheet bends no more than the exactly
    // constrained minimum; the motions the energy leaves free (tilting about the curve) stay
    // near the start.
    const auto energy = [&](const Eigen::MatrixX3d& p) { return (p.transpose() * h * p).trace(); };
    EXPECT_LT(energy(r.poles), 1.001 * energy(reference.poles));
    EXPECT_LT(sheet_gap(pb.space, r.poles, reference.poles), 0.02);
  }
}

}  // namespace

// give_up_early stops the refinement steps of a sheet too coarse for its tolerance (a fast wave
// on 2 spans) long before penalty_steps, still reporting the conflict, and leaves a sheet that
// meets the tolerance exactly as it was.
TEST(PenaltyMode, GivesUpEarlyOnlyWhereTheToleranceIsOutOfReach) {
  for (int spans : {2, 16}) {
    SheetProblem pb = rest_problem(3, spans, /*fix_boundary=*/false);
    pb.curves.push_back(curve_on(pb, {0.1, 0.4}, {0.9, 0.6}, 0.03, spans == 2 ? 0.01 : 0.0));
    pb.rest_poles.resize(0, 3);
    SolveOptions opt;
    opt.mode = SolveMode::penalty;
    opt.fit_tolerance = 1e-4;
    const SolveResult full = solve_sheet(pb, opt);
    opt.give_up_early = true;
    const SolveResult early = solve_sheet(pb, opt);
    SCOPED_TRACE(spans);
    if (spans == 2) {
      // All the configured weight's steps, after a few on a raised weight that missed too.
      EXPECT_GE(full.report.inner_iterations, opt.penalty_steps);
      EXPECT_LE(full.report.inner_iterations, opt.penalty_steps + 15);
      EXPECT_GT(full.report.conflict, opt.fit_tolerance);
      EXPECT_LT(early.report.inner_iterations, opt.penalty_steps / 4);
      EXPECT_GT(early.report.conflict, opt.fit_tolerance);
    } else {
      EXPECT_EQ(full.report.conflict, 0.0);
      EXPECT_EQ(early.report.inner_iterations, full.report.inner_iterations);
      EXPECT_EQ((early.poles - full.poles).cwiseAbs().maxCoeff(), 0.0);
    }
  }
}
