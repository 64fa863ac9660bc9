// SPDX-License-Identifier: LGPL-2.1-or-later
// The equality-constrained quadratic problem behind every sheet solve, and its solve modes.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "constraint_reduction.hpp"
#include "varsurf/core/sheet_solver.hpp"

namespace varsurf {

// minimize (x - rest)^T Q (x - rest) - 2 f^T x over the free columns subject to the constraint
// samples (reduced to independent rows), with fixed columns at x0 (rest empty: 0). Each column of
// f / x0 is one right-hand side sharing Q and the constraint matrix. The solve works on the
// displacement x - rest: a rest shape that nothing moves comes back exactly, however badly Q is
// conditioned (high degrees), instead of through Q^-1 (Q rest).
struct Quadratic {
  Eigen::SparseMatrix<double> q;
  Eigen::MatrixXd f;
  Eigen::MatrixXd x0;       // start values, and the values of fixed columns
  std::vector<bool> fixed;  // per column
  std::vector<ConstraintSamples> blocks;
  Eigen::MatrixXd rest;  // as x0, or empty
};

// Reduces the constraints and factors what the mode needs once; solve() may then be called for
// new right-hand sides (moved targets) at the cost of back-substitution.
class ConstrainedSolve {
 public:
  // earlier: a solve of the same energy (its constraints fewer by a few sample rows) whose
  // penalty factor may serve this one instead of a new factorization; it stays usable.
  ConstrainedSolve(const Quadratic& problem, const SolveOptions& options, SolveReport& report,
                   const ConstrainedSolve* earlier = nullptr);
  ~ConstrainedSolve();

  // All columns (fixed ones at x0) for energy right-hand side f and reduced constraint
  // right-hand side b (rank x width).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b,
                        SolveReport& report) const;

  const Eigen::MatrixXd& reduced_rhs() const;
  // The reduced right-hand side of moved samples (same matrices as the prepared ones).
  Eigen::MatrixXd reduced_rhs(const std::vector<ConstraintSamples>& moved) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace varsurf
