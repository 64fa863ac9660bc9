// SPDX-License-Identifier: LGPL-2.1-or-later
// A sheet's quadratic problem for solvers that combine several sheets (the model solver).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "constrained_solve.hpp"
#include "varsurf/core/sheet_solver.hpp"

namespace varsurf {

// Q (x) I_3 in the coupled ordering: column 3 k + c is coordinate c of pole k.
Eigen::SparseMatrix<double> kron_identity3(const Eigen::SparseMatrix<double>& q);

// n x 3 poles as one 3n column (rows 3 k + c), and back.
Eigen::MatrixXd flatten(const Eigen::MatrixX3d& m);
Eigen::MatrixX3d unflatten(const Eigen::MatrixXd& x);

// The sheet's energy, operators and constraints, fixed poles marked: in the coupled ordering
// (3 k + c) when force_coupled or when a term couples x, y and z (q is then 3n x 3n, blocks
// coupled), else separable (q n x n, x0 and f n x 3). InvalidInput for an invalid problem or for
// the iterated terms (pressure, repellers, shape attractors). With fold_rest the rest shape is
// moved into f (x^T Q x - 2 f^T x, for joint solves that add sheets' f together); without, it
// stays in Quadratic::rest.
Quadratic sheet_quadratic(const SheetProblem& problem, const SolveOptions& options, bool fold_rest,
                          bool force_coupled);

}  // namespace varsurf
