// SPDX-License-Identifier: LGPL-2.1-or-later
// A penalty factor kept when constraints are added (PreparedSheet::change).
//
// The factor F of K_o = Q + w_o B_o^T B_o + eps I serves K = Q + w B^T B + eps I, where B is B_o
// with k rows U added and w the weight the new constraints give (w depends on the mean of
// B^T B's diagonal, so it moves a little with every added row). P = K_o + w U^T U is solved
// exactly through F by the Sherman-Morrison-Woodbury formula (k back-substitutions once), and
// K x = r by conjugate gradients preconditioned by P: K - P = (w - w_o) B_o^T B_o (a pin among
// 14 curves moves w by 5 %, each constraint weighing the same), and the answer is K's own, as a
// fresh factorization's, not an approximation of a nearby system.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>

namespace varsurf {

class FactorCorrection {
 public:
  using Apply = std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>;

  // base: F^-1 (K_o^-1); added: the k added rows U; weight: w.
  FactorCorrection(const Apply& base, const Eigen::SparseMatrix<double, Eigen::RowMajor>& added,
                   double weight);

  // P^-1 y: one back-substitution of y's columns, and the rank-k correction.
  Eigen::MatrixXd precondition(const Eigen::MatrixXd& y) const;

  // K^-1 r (k: the product with K) into x; false when the refinement does not converge (the
  // weights too far apart, or K not positive definite), x then undefined. `substitutions` counts
  // the back-substitutions through F.
  bool solve(const Eigen::MatrixXd& r, const Apply& k, Eigen::MatrixXd& x,
             int& substitutions) const;

  // The back-substitutions made when the correction was set up (one per added row).
  int setup_substitutions() const { return static_cast<int>(w_.cols()); }

  static constexpr int kMaxSteps = 30;

 private:
  Apply base_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> u_;
  Eigen::MatrixXd w_;              // K_o^-1 U^T, n x k
  Eigen::LLT<Eigen::MatrixXd> c_;  // I / w + U K_o^-1 U^T, k x k
};

}  // namespace varsurf
