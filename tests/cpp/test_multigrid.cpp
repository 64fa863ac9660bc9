// SPDX-License-Identifier: LGPL-2.1-or-later
// Multigrid-preconditioned conjugate gradients on a sheet's B-spline levels: the direct solve's
// poles, in a number of steps that does not grow with the sheet.
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/multigrid.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;
using varsurf::test::with_mode;

namespace {

// Hermite data all round (two outer rings held) on a wavy start, the interior free.
SheetProblem held(int spans, bool pde) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, spans, spans);
  if (pde) {
    pb.pde = PdeCoefficient();
    pb.pde->a = 1.7;
  }
  const int nu = pb.space.nu(), nv = pb.space.nv();
  pb.initial_poles.resize(pb.space.size(), 3);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = static_cast<double>(i) / (nu - 1), v = static_cast<double>(j) / (nv - 1);
      pb.initial_poles.row(pb.space.index(i, j)) << 100 * u, 80 * v,
          10 * std::sin(3 * u) * std::cos(2 * v) + 5 * u * v;
      if (i < 2 || j < 2 || i >= nu - 2 || j >= nv - 2)
        pb.fixed_poles.push_back(pb.space.index(i, j));
      else
        pb.initial_poles(pb.space.index(i, j), 2) += 20.0;  // the start is not the answer
    }
  return pb;
}

}  // namespace

TEST(Multigrid, GivesTheDirectSolvesPoles) {
  for (bool pde : {true, false}) {
    const SheetProblem pb = held(32, pde);
    MultigridReport report;
    const SolveResult mg = solve_sheet_multigrid(pb, MultigridOptions(), &report);
    const SolveResult direct = solve_sheet(pb, with_mode(SolveMode::exact));
    EXPECT_EQ(direct.report.mode, SolveMode::exact);
    EXPECT_LT((mg.poles - direct.poles).cwiseAbs().maxCoeff(), 1e-8)
        << (pde ? "PDE" : "thin plate");
    EXPECT_GE(report.levels, 2);
    EXPECT_LE(report.residual, 1e-12);
  }
}

TEST(Multigrid, StepsDoNotGrowWithTheSheet) {
  int first = 0;
  for (int spans : {16, 32, 64, 128}) {
    MultigridReport report;
    solve_sheet_multigrid(held(spans, true), MultigridOptions(), &report);
    if (first == 0) first = report.iterations;
    EXPECT_LE(report.iterations, 2 * first + 5) << spans << " spans";
    EXPECT_LE(report.iterations, 60) << spans << " spans";
  }
}

TEST(Multigrid, OnlySheetsHeldByFixedPolesAreTaken) {
  SheetProblem pb = held(8, true);
  pb.points.push_back({0.5, 0.5, Eigen::Vector3d::Zero(), 1.0});
  EXPECT_THROW(solve_sheet_multigrid(pb, MultigridOptions()), InvalidInput);
  pb = held(8, true);
  pb.initial_poles.conservativeResize(10, 3);
  EXPECT_THROW(solve_sheet_multigrid(pb, MultigridOptions()), InvalidInput);
  MultigridOptions bad;
  bad.tolerance = 0.0;
  EXPECT_THROW(solve_sheet_multigrid(held(8, true), bad), InvalidInput);
}

TEST(Multigrid, AutomaticTakesItForLargeSheetsHeldByFixedPoles) {
  // 67 x 67 poles, 3969 free: above multigrid_from, with three levels; with a rest shape too
  // (the PDE displacement of an existing face).
  for (bool rest : {false, true}) {
    SheetProblem pb = held(64, true);
    if (rest) {
      pb.rest_poles = pb.initial_poles;
      for (int k = 0; k < pb.space.size(); ++k) pb.rest_poles(k, 2) += 3.0 * std::sin(0.01 * k);
    }
    const SolveResult automatic = solve_sheet(pb);
    const SolveResult direct = solve_sheet(pb, with_mode(SolveMode::exact));
    EXPECT_EQ(automatic.report.mode, SolveMode::multigrid);
    EXPECT_NE(automatic.report.mode_reason.find("multigrid"), std::string::npos);
    EXPECT_EQ(direct.report.mode, SolveMode::exact);
    EXPECT_LT((automatic.poles - direct.poles).cwiseAbs().maxCoeff(), 1e-8) << rest;
    EXPECT_EQ(automatic.report.unknowns, 63 * 63);
    // The fixed poles stay where they were given.
    for (int k : pb.fixed_poles) EXPECT_EQ(automatic.poles.row(k), pb.initial_poles.row(k));
  }
}

TEST(Multigrid, AutomaticKeepsTheDirectSolveElsewhere) {
  // Below the threshold (13 x 13 free poles), with a constraint, with nothing to coarsen to (odd
  // spans).
  EXPECT_NE(solve_sheet(held(16, true)).report.mode, SolveMode::multigrid);
  SheetProblem pb = held(64, true);
  pb.points.push_back({0.5, 0.5, Eigen::Vector3d(50, 40, 30), 1.0});
  const SolveResult pinned = solve_sheet(pb);
  EXPECT_NE(pinned.report.mode, SolveMode::multigrid);
  EXPECT_THROW(solve_sheet(pb, with_mode(SolveMode::multigrid)), InvalidInput);
  EXPECT_NE(solve_sheet(held(63, true)).report.mode, SolveMode::multigrid);
  // Asked of a joined or prepared solve, which multigrid does not do: refused.
  EXPECT_THROW(PreparedSheet(held(16, true), with_mode(SolveMode::multigrid)), InvalidInput);
}

TEST(Multigrid, AutomaticFallsBackWhenTheFixedPolesDoNotHoldTheSheet) {
  // Bending alone with two corner poles held: an affine motion vanishing on their diagonal costs
  // nothing. Multigrid declines (a singular coarsest level) and the direct solve keeps that
  // motion where it started.
  SheetProblem pb = held(64, false);
  pb.energy = ThinPlateWeights::isotropic(0.0, 1.0);
  pb.fixed_poles = {0, pb.space.size() - 1};
  SolveOptions o;
  o.multigrid_from = 0;
  const SolveResult automatic = solve_sheet(pb, o);
  EXPECT_NE(automatic.report.mode, SolveMode::multigrid);
  EXPECT_NE(automatic.report.mode_reason.find("multigrid declined"), std::string::npos)
      << automatic.report.mode_reason;
  const SolveResult direct = solve_sheet(pb, with_mode(SolveMode::exact));
  EXPECT_LT((automatic.poles - direct.poles).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_THROW(solve_sheet(pb, with_mode(SolveMode::multigrid)), SolveFailure);
}

TEST(Multigrid, AutomaticIsCancelledAndTimedLikeTheDirectSolve) {
  // Cancelled between conjugate gradient steps (not taken for a failure to fall back from), and
  // stopped by the time limit.
  SolveOptions cancelled;
  int asked = 0;
  cancelled.keep_going = [&asked] { return ++asked < 2; };
  EXPECT_THROW(solve_sheet(held(64, true), cancelled), Cancelled);
  EXPECT_GE(asked, 2);
  SolveOptions timed;
  timed.time_limit = 1e-6;
  EXPECT_THROW(solve_sheet(held(128, true), timed), ResourceLimit);
}
