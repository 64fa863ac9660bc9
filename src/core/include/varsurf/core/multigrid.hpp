// SPDX-License-Identifier: LGPL-2.1-or-later
// Multigrid on a sheet's B-spline levels (Du & Qin sec. 4.3 solve coarse first and refine; here
// as the preconditioner of conjugate gradients): the levels halve the spans, knot insertion
// (refinement_matrix) prolongs a coarse correction exactly, each coarse operator is the Galerkin
// product P^T A P, symmetric Gauss-Seidel smooths, the coarsest level is factored. It needs no
// factor of the fine matrix: its memory grows with the matrix, not with a factor's fill.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <vector>

#include "varsurf/core/sheet_solver.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf {

struct MultigridOptions {
  int smoothing = 2;         // symmetric Gauss-Seidel sweeps before and after each correction
  int coarsest_poles = 400;  // levels are added down to about this many free poles
  double tolerance = 1e-12;  // relative residual at which conjugate gradients stop
  int max_iterations = 500;
  // Asked between conjugate gradient steps; false stops the solve with Cancelled. Empty: never.
  std::function<bool()> keep_going;
};

struct MultigridReport {
  int levels = 0;
  int iterations = 0;     // conjugate gradient steps (largest of x, y, z)
  double residual = 0.0;  // relative, largest of x, y, z
  double setup_seconds = 0.0, solve_seconds = 0.0;
  long long stored_entries = 0;  // nonzeros of every level's matrix and prolongation
};

// Q x = f for the free poles, the `fixed` ones held at x0 (Q: size() x size(), symmetric positive
// definite on the free poles; f, x0: size() x 3). Levels coarsen while every interior knot is
// simple and the span count even. InvalidInput for mismatched sizes, SolveFailure when conjugate
// gradients do not reach the tolerance within max_iterations.
Eigen::MatrixX3d solve_multigrid(const SplineSpace& space, const Eigen::SparseMatrix<double>& q,
                                 const Eigen::MatrixX3d& f, const Eigen::MatrixX3d& x0,
                                 const std::vector<int>& fixed, const MultigridOptions& options,
                                 MultigridReport* report = nullptr);

// Whether the problem is a sheet held by its fixed poles alone (no constraint rows, operators,
// pressure, closure or kept region; a rest shape allowed) on a non-rational space.
bool held_by_fixed_poles_alone(const SheetProblem& problem);

// Whether the space has a coarser level (simple interior knots, an even count of at least 4
// spans in both directions): without one multigrid is a direct solve.
bool has_coarser_level(const SplineSpace& space);

// A sheet held by its fixed poles alone: its energy minimized by solve_multigrid. InvalidInput
// for other problems.
SolveResult solve_sheet_multigrid(const SheetProblem& problem, const MultigridOptions& options,
                                  MultigridReport* report = nullptr);

}  // namespace varsurf
