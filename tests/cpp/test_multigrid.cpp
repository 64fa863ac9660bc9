// SPDX-License-Identifier: LGPL-2.1-or-later
// Multigrid-preconditioned conjugate gradients on a sheet's B-spline levels: the direct solve's
// poles, in a number of steps that does not grow with the sheet.
#include <gtest/gtest.h>

#include <cmath>

#include "varsurf/core/errors.hpp"
#include "varsurf/core/multigrid.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

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
    const SolveResult direct = solve_sheet(pb);
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
