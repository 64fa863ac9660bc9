// SPDX-License-Identifier: LGPL-2.1-or-later
// Solve modes (exact, penalty, CG, TSVD, MTSVD, automatic), the L-curve, and reuse of a
// factorization when only targets move.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/lcurve.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

namespace {

using test::flat_poles;
using test::with_mode;

PointConstraint pin(double u, double v, const Eigen::Vector3d& target) {
  PointConstraint p;
  p.u = u;
  p.v = v;
  p.target = target;
  return p;
}

// A flat unit sheet with its boundary held and a thin plate under a little tension.
SheetProblem flat_problem(int spans) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, spans, spans);
  pb.initial_poles = flat_poles(pb.space);
  pb.fixed_poles = boundary_pole_indices(pb.space);
  pb.energy = ThinPlateWeights::isotropic(0.1, 1.0);
  return pb;
}

// A wavy curve over a non-isoparametric line, a pin and a fixed boundary: the energy decides
// most poles (under-determined constraints).
SheetProblem curve_problem(int spans) {
  SheetProblem pb = flat_problem(spans);
  CurveConstraint c;
  c.preimage = test::line_curve(Eigen::Vector2d(0.2, 0.25), Eigen::Vector2d(0.8, 0.7));
  std::vector<double> fine;
  for (int i = 0; i <= 32; ++i) fine.push_back(i / 32.0);
  c.target = test::fit_piecewise_curve(fine, 5, 3, [](double t) {
    return Eigen::VectorXd(Eigen::Vector3d(0.2 + 0.6 * t, 0.25 + 0.45 * t, 0.1 * std::sin(4 * t)));
  });
  pb.curves.push_back(c);
  pb.points.push_back(pin(0.3, 0.7, {0.3, 0.7, 0.15}));
  return pb;
}

// Well-posed constraints: a curve on the iso line v = 0.5 whose target is that line's image on
// a smooth sheet of the same space (exactly representable, well conditioned), two pins and a
// tangent; the energy decides the rest.
SheetProblem well_posed_problem(int spans) {
  SheetProblem pb = flat_problem(spans);
  const Eigen::MatrixX3d smooth = test::fit_poles(pb.space, [](double u, double v) {
    return Eigen::Vector3d(u, v, 0.2 * std::sin(3 * u) * std::sin(3.1 * v));
  });
  CurveConstraint c;
  c.preimage = test::line_curve(Eigen::Vector2d(0.0, 0.5), Eigen::Vector2d(1.0, 0.5));
  c.target.degree = 3;
  c.target.knots = pb.space.knots_u;
  // Pole i of the iso curve is sum_j N_j(0.5) P_ij; N_j(0.5) read off a basis sample at u = 0,
  // where only the first u function is non-zero (and equals 1).
  const SplineSpace& sp = pb.space;
  c.target.poles = Eigen::MatrixXd::Zero(sp.nu(), 3);
  const BasisSample bs = sp.basis(0.0, 0.5, 0);
  for (size_t k = 0; k < bs.index.size(); ++k) {
    const int j = bs.index[k] % sp.nv();
    const double nj = bs.values(0, static_cast<Eigen::Index>(k));
    for (int i = 0; i < sp.nu(); ++i) c.target.poles.row(i) += nj * smooth.row(sp.index(i, j));
  }
  pb.curves.push_back(c);
  pb.points.push_back(pin(0.3, 0.25, {0.3, 0.25, 0.1}));
  pb.points.push_back(pin(0.7, 0.8, {0.7, 0.8, -0.05}));
  TangentConstraint tc;
  tc.u = 0.6;
  tc.v = 0.2;
  tc.direction = 0;
  tc.target = Eigen::Vector3d(1.0, 0.0, 0.3);
  pb.tangents.push_back(tc);
  return pb;
}

// A normal prescribed at (0.6, 0.3): a constraint that couples x, y and z.
NormalConstraint tilted_normal() {
  NormalConstraint nc;
  nc.u = 0.6;
  nc.v = 0.3;
  nc.normal = Eigen::Vector3d(0.2, 0.1, 1.0);
  return nc;
}

}  // namespace

TEST(SolveModes, EnergyModesAgreeOnAWellPosedProblem) {
  for (bool coupled : {false, true}) {
    SheetProblem pb = well_posed_problem(8);
    if (coupled) pb.normals.push_back(tilted_normal());
    const SolveResult exact = solve_sheet(pb, with_mode(SolveMode::exact));
    EXPECT_EQ(exact.report.mode, SolveMode::exact);
    EXPECT_EQ(exact.report.coupled, coupled);
    for (SolveMode mode :
         {SolveMode::penalty, SolveMode::cg, SolveMode::mtsvd, SolveMode::automatic}) {
      const SolveResult r = solve_sheet(pb, with_mode(mode));
      EXPECT_LT((r.poles - exact.poles).cwiseAbs().maxCoeff(), 1e-8)
          << to_string(mode) << " coupled " << coupled << " inner " << r.report.inner_iterations;
      EXPECT_EQ(r.report.mode, mode == SolveMode::automatic ? SolveMode::exact : mode);
      EXPECT_FALSE(r.report.mode_reason.empty());
    }
  }
}

TEST(SolveModes, KeepGoingIsAskedAndCanStopTheIterativeModes) {
  const SheetProblem pb = well_posed_problem(8);
  for (SolveMode mode : {SolveMode::penalty, SolveMode::cg}) {
    SolveOptions opt = with_mode(mode);
    const SolveResult plain = solve_sheet(pb, opt);
    int asked = 0;
    opt.keep_going = [&asked] { return ++asked > 0; };
    const SolveResult watched = solve_sheet(pb, opt);
    EXPECT_GT(asked, 0) << to_string(mode);
    EXPECT_EQ((watched.poles - plain.poles).cwiseAbs().maxCoeff(), 0.0) << to_string(mode);
    asked = 0;
    opt.keep_going = [&asked] { return ++asked < 2; };
    EXPECT_THROW(solve_sheet(pb, opt), Cancelled) << to_string(mode);
    EXPECT_EQ(asked, 2) << to_string(mode);
  }
}

TEST(SolveModes, PenaltyByQrEqualsPenaltyByCholesky) {
  // Welch & Witkin's eq. 10 factored as the stacked least-squares system (sparse QR) and through
  // its normal equations (sparse Cholesky): the same minimizer, on a well-posed problem both equal
  // the exact solve.
  for (bool coupled : {false, true}) {
    SheetProblem pb = well_posed_problem(8);
    if (coupled) pb.normals.push_back(tilted_normal());
    SolveOptions qr = with_mode(SolveMode::penalty);
    qr.penalty_qr = true;
    const SolveResult by_qr = solve_sheet(pb, qr);
    const SolveResult by_cholesky = solve_sheet(pb, with_mode(SolveMode::penalty));
    const SolveResult exact = solve_sheet(pb, with_mode(SolveMode::exact));
    EXPECT_LT((by_qr.poles - by_cholesky.poles).cwiseAbs().maxCoeff(), 1e-8) << coupled;
    EXPECT_LT((by_qr.poles - exact.poles).cwiseAbs().maxCoeff(), 1e-8) << coupled;
  }
}

TEST(SolveModes, ReducedModesAgreeOnAnIllConditionedCurve) {
  // A wavy curve over a slanted line: its incidence has singular values down to the rank
  // tolerance. Exact, CG and MTSVD share the reduced rows and agree; the penalty mode fits weak
  // directions only as far as the tolerance asks (below).
  const SheetProblem pb = curve_problem(8);
  const SolveResult exact = solve_sheet(pb, with_mode(SolveMode::exact));
  for (SolveMode mode : {SolveMode::cg, SolveMode::mtsvd}) {
    const SolveResult r = solve_sheet(pb, with_mode(mode));
    EXPECT_LT((r.poles - exact.poles).cwiseAbs().maxCoeff(), 1e-8) << to_string(mode);
  }
}

TEST(SolveModes, PenaltyRefinesUntilEveryConstraintIsWithinTolerance) {
  SheetProblem pb = curve_problem(8);
  for (double tolerance : {1e-3, 1e-4, 1e-5}) {
    SolveOptions o = with_mode(SolveMode::penalty);
    o.fit_tolerance = tolerance;
    const SolveResult r = solve_sheet(pb, o);
    EXPECT_EQ(r.report.conflict, 0.0) << tolerance;
    // RMS of each constraint on the result, measured independently of the solver.
    double sum = 0.0;
    const CurveConstraint& c = pb.curves[0];
    for (int k = 0; k <= 400; ++k) {
      const double t = k / 400.0;
      const Eigen::VectorXd uv = c.preimage.evaluate(t);
      sum += (evaluate_surface(pb.space, r.poles, uv(0), uv(1), 0).row(0).transpose() -
              c.target.evaluate(t))
                 .squaredNorm();
    }
    EXPECT_LT(std::sqrt(sum / 401), 1.5 * tolerance) << tolerance;
    EXPECT_LT(
        (evaluate_surface(pb.space, r.poles, 0.3, 0.7, 0).row(0).transpose() - pb.points[0].target)
            .norm(),
        tolerance)
        << tolerance;
    EXPECT_GE(r.report.inner_iterations, 1);
  }
}

TEST(SolveModes, PenaltyEndsOnAnEnergyScaleNearTheSmallestDouble) {
  // An energy weight of 1e-320 (a denormal) makes the energy's scale underflow the penalty's
  // regularization ladder to 0: it once retried eps = 0 forever (found by fuzzing). The solve must
  // end, with finite poles that meet the pin or with a SolveFailure.
  for (double weight : {1e-323, 1e-321, 1e-320, 1e-318, 1e-310, 1e300}) {
    SheetProblem pb = flat_problem(4);
    pb.fixed_poles.clear();
    pb.energy = ThinPlateWeights::isotropic(weight, 0.0);
    pb.points.push_back(pin(0.5, 0.5, {0.5, 0.5, 0.2}));
    try {
      const SolveResult r = solve_sheet(pb, with_mode(SolveMode::penalty));
      ASSERT_TRUE(r.poles.allFinite()) << weight;
      EXPECT_LT((evaluate_surface(pb.space, r.poles, 0.5, 0.5, 0).row(0).transpose() -
                 pb.points[0].target)
                    .norm(),
                1e-3)
          << weight;
    } catch (const SolveFailure&) {
    }
  }
}

TEST(SolveModes, EveryModeAgreesWhenTheConstraintsDetermineThePoles) {
  // Fixed boundary and one pin per interior pole at its Greville point: the constraints alone
  // determine the sheet, so TSVD (which ignores the energy) must agree too.
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, 5, 5);
  pb.initial_poles = flat_poles(pb.space);
  pb.fixed_poles = boundary_pole_indices(pb.space);
  pb.energy = ThinPlateWeights::isotropic(0.1, 1.0);
  const std::vector<double> g = test::greville(pb.space.knots_u, 3);
  for (size_t i = 1; i + 1 < g.size(); ++i)
    for (size_t j = 1; j + 1 < g.size(); ++j)
      pb.points.push_back(pin(g[i], g[j], {g[i], g[j], 0.1 * std::sin(3 * g[i] + 2 * g[j])}));
  const SolveResult exact = solve_sheet(pb, with_mode(SolveMode::exact));
  for (SolveMode mode : {SolveMode::penalty, SolveMode::cg, SolveMode::tsvd, SolveMode::mtsvd}) {
    const SolveResult r = solve_sheet(pb, with_mode(mode));
    EXPECT_LT((r.poles - exact.poles).cwiseAbs().maxCoeff(), 1e-8) << to_string(mode);
  }
}

TEST(LCurve, CornerMatchesAKnownNoiseLevel) {
  // sigma_i = 10^(-(i-1)/4); exact data with Picard coefficients sigma_i^1.5 plus noise of size
  // delta in every direction. The solution's coefficients sigma_i^0.5 are above the noise's
  // delta / sigma_i until sigma_i ~ delta^(2/3): for delta = 1e-6, sigma ~ 1e-4, i ~ 17.
  const int n = 64;
  Eigen::VectorXd sigma(n), gain(n);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> sign(-1.0, 1.0);
  for (int i = 0; i < n; ++i) {
    sigma(i) = std::pow(10.0, -i / 4.0);
    const double beta = std::pow(sigma(i), 1.5) + 1e-6 * (sign(rng) > 0 ? 1.0 : -1.0);
    gain(i) = beta * beta;
  }
  const LCurve curve = lcurve(sigma, gain, gain.sum() + 1e-10);
  ASSERT_EQ(curve.k.size(), static_cast<size_t>(n));
  EXPECT_GE(curve.corner, 13);
  EXPECT_LE(curve.corner, 22);
  // The legs: residuals fall and solution norms grow with k.
  for (size_t i = 1; i < curve.k.size(); ++i) {
    EXPECT_LE(curve.residual[i], curve.residual[i - 1] * (1 + 1e-12));
    EXPECT_GE(curve.solution_norm[i], curve.solution_norm[i - 1]);
  }
  // Without noise nor ill-conditioning there is no corner: everything is kept.
  Eigen::VectorXd mild(8), g8(8);
  for (int i = 0; i < 8; ++i) {
    mild(i) = 1.0 - 0.1 * i;
    g8(i) = 1.0;
  }
  EXPECT_EQ(lcurve(mild, g8, 8.0).corner, 8);
  EXPECT_THROW(lcurve(g8.reverse().eval() * 0.0, g8, 8.0), InvalidInput);
}

namespace {

// Largest second difference of the control net along u and v: the "staircase" measure.
double net_roughness(const SplineSpace& sp, const Eigen::MatrixX3d& p) {
  double worst = 0.0;
  for (int i = 0; i < sp.nu(); ++i)
    for (int j = 0; j < sp.nv(); ++j) {
      if (i > 0 && i + 1 < sp.nu())
        worst = std::max(worst, (p.row(sp.index(i - 1, j)) - 2 * p.row(sp.index(i, j)) +
                                 p.row(sp.index(i + 1, j)))
                                    .norm());
      if (j > 0 && j + 1 < sp.nv())
        worst = std::max(worst, (p.row(sp.index(i, j - 1)) - 2 * p.row(sp.index(i, j)) +
                                 p.row(sp.index(i, j + 1)))
                                    .norm());
    }
  return worst;
}

// Thin-plate bending energy of the sheet, summed over x, y, z.
double bending(const SplineSpace& sp, const Eigen::MatrixX3d& p) {
  const Eigen::SparseMatrix<double> h =
      assemble_thin_plate(sp, ThinPlateWeights::isotropic(0.0, 1.0));
  return (p.transpose() * (h * p)).trace();
}

double rms_incidence(const SplineSpace& sp, const Eigen::MatrixX3d& poles,
                     const CurveConstraint& c) {
  double sum = 0.0;
  const int n = 400;
  for (int k = 0; k <= n; ++k) {
    const double t = c.preimage.first() + (c.preimage.last() - c.preimage.first()) * k / n;
    const Eigen::VectorXd uv = c.preimage.evaluate(t);
    sum += (evaluate_surface(sp, poles, uv(0), uv(1), 0).row(0).transpose() - c.target.evaluate(t))
               .squaredNorm();
  }
  return std::sqrt(sum / (n + 1));
}

// Michalik & Bruderlin's case: a bicubic 8 x 10 sheet, free boundary, one curve over a
// non-isoparametric line whose target carries a ripple (amplitude 2e-3) that the space cannot
// hold: noisy data, an ill-posed system.
SheetProblem rippled_curve_problem() {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, 5, 7);
  pb.initial_poles = flat_poles(pb.space);
  pb.energy = ThinPlateWeights::isotropic(0.1, 1.0);
  CurveConstraint c;
  c.preimage = test::line_curve(Eigen::Vector2d(0.05, 0.1), Eigen::Vector2d(0.95, 0.8));
  std::vector<double> fine;
  for (int i = 0; i <= 256; ++i) fine.push_back(i / 256.0);
  c.target = test::fit_piecewise_curve(fine, 5, 3, [](double t) {
    return Eigen::VectorXd(Eigen::Vector3d(0.05 + 0.9 * t, 0.1 + 0.7 * t,
                                           0.15 * std::sin(5 * t) + 2e-3 * std::sin(90 * t)));
  });
  pb.curves.push_back(c);
  return pb;
}

}  // namespace

TEST(SolveModes, MtsvdRemovesTheAliasingOfTsvdOnAnIllPosedCurve) {
  // TSVD keeps the L-curve's stable directions and
  // moves the rest of the poles least (the staircase); MTSVD keeps the same directions and lets
  // the thin-plate energy place the rest.
  const SheetProblem pb = rippled_curve_problem();
  const CurveConstraint& c = pb.curves[0];
  const SolveResult tsvd = solve_sheet(pb, with_mode(SolveMode::tsvd));
  const SolveResult mtsvd = solve_sheet(pb, with_mode(SolveMode::mtsvd));
  const LCurve& lc = tsvd.report.lcurve;
  EXPECT_EQ(lc.corner, mtsvd.report.lcurve.corner);
  EXPECT_GT(lc.corner, 5);
  EXPECT_LT(lc.corner, static_cast<int>(lc.k.size()));  // the noise is not fitted
  const double rough_t = net_roughness(pb.space, tsvd.poles);
  const double rough_m = net_roughness(pb.space, mtsvd.poles);
  const double bend_t = bending(pb.space, tsvd.poles), bend_m = bending(pb.space, mtsvd.poles);
  // Measured: corner 14 of 43, net roughness 0.238 vs 0.125, bending 20.2 vs 3.8.
  EXPECT_LT(rough_m, 0.6 * rough_t);
  EXPECT_LT(bend_m, 0.25 * bend_t);
  // Both meet the curve within its ripple (RMS 1.4e-3): the smooth part is fitted, the noise not.
  EXPECT_LT(rms_incidence(pb.space, tsvd.poles, c), 2e-3);
  EXPECT_LT(rms_incidence(pb.space, mtsvd.poles, c), 2e-3);
}

TEST(SolveModes, KrylovTruncationForLargeConstraintGroups) {
  // The same ill-posed case through the Krylov path (forced by a low limit): CGLS iterations
  // stopped at the L-curve's corner stand in for the truncated SVD; MTSVD then lets the energy
  // place what that fit leaves free.
  const SheetProblem pb = rippled_curve_problem();
  const CurveConstraint& c = pb.curves[0];
  SolveOptions o = with_mode(SolveMode::tsvd);
  o.krylov_limit = 10;
  const SolveResult tsvd = solve_sheet(pb, o);
  o.mode = SolveMode::mtsvd;
  const SolveResult mtsvd = solve_sheet(pb, o);
  for (const SolveResult* r : {&tsvd, &mtsvd}) {
    EXPECT_NE(r->report.mode_reason.find("Krylov"), std::string::npos) << r->report.mode_reason;
    const LCurve& lc = r->report.lcurve;
    ASSERT_GT(lc.k.size(), 3u);
    EXPECT_GT(lc.corner, 1);
    if (r == &tsvd) {
      EXPECT_EQ(r->report.inner_iterations, lc.corner);
    }
    EXPECT_LT(rms_incidence(pb.space, r->poles, c), 3e-3) << to_string(r->report.mode);
  }
  // The energy norm places what the constraints leave free: a smoother sheet.
  EXPECT_LT(bending(pb.space, mtsvd.poles), 0.5 * bending(pb.space, tsvd.poles));
}

TEST(PreparedSheet, MovedTargetsEqualAFreshSolve) {
  // Directions weaker than 1e-5 of the strongest are dropped, so that rounding in the data
  // (amplified by 1 / sigma) stays below the comparison's 1e-10.
  for (SolveMode mode : {SolveMode::exact, SolveMode::penalty, SolveMode::cg}) {
    for (bool coupled : {false, true}) {
      // The penalty mode fits to convergence only well-conditioned constraints quickly.
      SheetProblem pb = mode == SolveMode::penalty ? well_posed_problem(10) : curve_problem(10);
      if (coupled) {
        PlanePointConstraint pp;
        pp.u = 0.6;
        pp.v = 0.3;
        pp.origin = Eigen::Vector3d(0, 0, 0.05);
        pp.normal = Eigen::Vector3d(0.1, 0, 1);
        pb.plane_points.push_back(pp);
      }
      SolveOptions options = with_mode(mode);
      options.rank_tolerance = 1e-5;
      PreparedSheet prepared(pb, options);
      SheetProblem moved = pb;
      moved.points[0].target += Eigen::Vector3d(0.01, -0.02, 0.1);  // a drag
      // The curve moved rigidly (same pre-image, same arc length): up and sideways.
      moved.curves[0].target.poles.rowwise() += Eigen::RowVector3d(0.02, 0.0, 0.05);
      if (coupled) moved.plane_points[0].origin.z() = 0.08;
      const SolveResult updated = prepared.update(moved);
      const SolveResult fresh = solve_sheet(moved, options);
      EXPECT_LT((updated.poles - fresh.poles).cwiseAbs().maxCoeff(), 1e-10)
          << to_string(mode) << " coupled " << coupled;
      EXPECT_GT((updated.poles - prepared.result().poles).cwiseAbs().maxCoeff(), 1e-3);
    }
  }
}

TEST(PreparedSheet, LCurveModesKeepTheirTruncationWhileDragging) {
  SheetProblem pb = curve_problem(8);
  PreparedSheet prepared(pb, with_mode(SolveMode::mtsvd));
  SheetProblem moved = pb;
  moved.points[0].target.z() += 0.05;
  const SolveResult r = prepared.update(moved);
  EXPECT_EQ(r.report.lcurve.corner, prepared.result().report.lcurve.corner);
  EXPECT_LT(r.report.constraint_residual, 1e-10);
  EXPECT_GT((r.poles - prepared.result().poles).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(PreparedSheet, AddedAndRemovedConstraintsEqualAFreshSolve) {
  for (SolveMode mode : {SolveMode::exact, SolveMode::penalty}) {
    SolveOptions options = with_mode(mode);
    options.rank_tolerance = 1e-5;
    SheetProblem pb = mode == SolveMode::penalty ? well_posed_problem(10) : curve_problem(10);
    PreparedSheet prepared(pb, options);
    // A pin added, then a second curve, then the first pin removed; each equals a fresh solve,
    // and a drag after a change still works.
    SheetProblem changed = pb;
    changed.points.push_back(pin(0.55, 0.45, {0.55, 0.45, 0.12}));
    const SolveResult added = prepared.change(changed);
    EXPECT_LT((added.poles - solve_sheet(changed, options).poles).cwiseAbs().maxCoeff(), 1e-10)
        << to_string(mode);
    CurveConstraint second;
    // An iso line (well conditioned, so the penalty refinement converges fully).
    second.preimage = test::line_curve(Eigen::Vector2d(0.85, 0.6), Eigen::Vector2d(0.85, 0.95));
    second.target =
        test::line_curve(Eigen::Vector3d(0.85, 0.6, 0.0), Eigen::Vector3d(0.85, 0.95, 0.05));
    changed.curves.push_back(second);
    changed.points.erase(changed.points.begin());
    const SolveResult changed_twice = prepared.change(changed);
    EXPECT_LT((changed_twice.poles - solve_sheet(changed, options).poles).cwiseAbs().maxCoeff(),
              1e-10)
        << to_string(mode);
    changed.points[0].target.z() += 0.03;
    EXPECT_LT((prepared.update(changed).poles - solve_sheet(changed, options).poles)
                  .cwiseAbs()
                  .maxCoeff(),
              1e-10)
        << to_string(mode);
    // A coupled constraint added to a separable sheet: prepared again, same answer.
    changed.normals.push_back(tilted_normal());
    EXPECT_LT((prepared.change(changed).poles - solve_sheet(changed, options).poles)
                  .cwiseAbs()
                  .maxCoeff(),
              1e-10)
        << to_string(mode);
  }
}

TEST(PreparedSheet, DraggingOneCurveThenAnotherEqualsFreshSolves) {
  // Updates keep the curves' samples between calls and re-evaluate only targets that moved:
  // curve A dragged, then curve B (A stays where it was dragged), then A back to where it was
  // prepared, a refused update, B again; each equals a fresh solve. Every direction is
  // fitted (no fit tolerance: nothing is held or truncated at preparation) and directions weaker
  // than 1e-5 of the strongest are dropped, so that only rounding separates the two.
  for (bool coupled : {false, true}) {
    for (SolveMode mode : {SolveMode::penalty, SolveMode::exact}) {
      // The penalty mode fits to convergence only well-conditioned constraints quickly.
      SheetProblem pb = mode == SolveMode::penalty ? well_posed_problem(10) : curve_problem(10);
      CurveConstraint second;  // an iso line
      second.preimage = test::line_curve(Eigen::Vector2d(0.85, 0.6), Eigen::Vector2d(0.85, 0.95));
      second.target =
          test::line_curve(Eigen::Vector3d(0.85, 0.6, 0.0), Eigen::Vector3d(0.85, 0.95, 0.05));
      pb.curves.push_back(second);
      if (coupled) pb.normals.push_back(tilted_normal());
      SolveOptions options = with_mode(mode);
      options.rank_tolerance = 1e-5;
      options.fit_tolerance = 0.0;
      PreparedSheet prepared(pb, options);
      SheetProblem moved = pb;
      const auto expect_fresh = [&](const char* step) {
        const SolveResult updated = prepared.update(moved);
        EXPECT_LT((updated.poles - solve_sheet(moved, options).poles).cwiseAbs().maxCoeff(), 1e-10)
            << step << " " << to_string(mode) << " coupled " << coupled;
        EXPECT_GT((updated.poles - prepared.result().poles).cwiseAbs().maxCoeff(), 1e-4) << step;
      };
      // Rigid moves: the same arc-length weights, so updates rather than changes.
      moved.curves[0].target.poles.col(2).array() += 0.04;
      expect_fresh("A dragged");
      moved.curves[1].target.poles.col(2).array() -= 0.03;
      expect_fresh("B dragged");
      moved.curves[0].target.poles = pb.curves[0].target.poles;
      expect_fresh("A back");
      SheetProblem replaced = moved;
      replaced.points[0].u += 0.05;  // re-placed, not moved: refused
      EXPECT_THROW(prepared.update(replaced), InvalidInput);
      moved.curves[1].target.poles.col(1).array() += 0.01;
      expect_fresh("B dragged again");
    }
  }
}

TEST(PreparedSheet, RefusesChangesBeyondTargets) {
  SheetProblem pb = curve_problem(6);
  PreparedSheet prepared(pb);
  SheetProblem other = pb;
  other.points[0].u = 0.4;  // re-placed, not moved
  EXPECT_THROW(prepared.update(other), InvalidInput);
  other = pb;
  other.points.push_back(pin(0.5, 0.5, {0.5, 0.5, 0.0}));
  EXPECT_THROW(prepared.update(other), InvalidInput);
  other = pb;
  other.energy = ThinPlateWeights::isotropic(1.0, 1.0);
  EXPECT_THROW(prepared.update(other), InvalidInput);
  other = pb;
  other.pressure = 1.0;
  EXPECT_THROW(prepared.update(other), InvalidInput);
  SheetProblem nonlinear = pb;
  nonlinear.pressure = 0.1;
  EXPECT_THROW(PreparedSheet{nonlinear}, InvalidInput);
}
