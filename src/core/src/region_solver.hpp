// SPDX-License-Identifier: LGPL-2.1-or-later
// One level's step of a detail edit (Boier-Martin, Ronfard & Bernardini sec. 4.3): the move x of
// a region's unknowns minimizing x^T H x subject to A x = c, for every column of c at once (the
// three coordinates when the constraints are points only; one column for the coupled system that
// normal constraints need, sec. 5).
#pragma once

#include <Eigen/Core>
#include <Eigen/QR>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <vector>

#include "varsurf/core/detail_edit.hpp"

namespace varsurf {

class RegionSolver {
 public:
  // h: the energy on the region's unknowns (approximate ignores it); a: the constraints' rows on
  // them. InvalidInput (naming `level`) when the constraints cannot be met even in least squares.
  RegionSolver(const Eigen::SparseMatrix<double>& h, const Eigen::SparseMatrix<double>& a,
               const DetailEditOptions& options, int level);
  // SOR stops when a sweep moves no unknown more than `stop`; its sweeps are added to `sweeps`.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& c, double stop, int& sweeps) const;

 private:
  DetailEditOptions options_;
  Eigen::SparseMatrix<double> h_, a_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> kkt_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> penalty_;
  double penalty_weight_ = 0.0;
  bool least_squares_ = false;
  // Approximate and SOR: the masks' least-norm move, by a sparse factorization of A A^T, or
  // densely where the masks are dependent.
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> sparse_masks_;
  bool dense_masks_ = false;
  Eigen::MatrixXd dense_a_;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> masks_;
  std::vector<Eigen::Index> relaxed_;  // SOR: the unknowns outside every mask
};

}  // namespace varsurf
