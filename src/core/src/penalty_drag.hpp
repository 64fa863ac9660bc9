// SPDX-License-Identifier: LGPL-2.1-or-later
// The penalty mode's drag step without a back-substitution of the whole factor.
//
// A penalty step solves K x = g + eps x0 + mu^2 B^T d_k (K = Q + mu^2 B^T B + eps I). When the
// last solve stopped after its first step, x1, and the data d moved since only by translations T_b
// of whole constraints (a dragged point, a curve moved along by its handle: the rows of block b
// move by s_r T_b, s_r the square root of the row's weight), the new first step is
//   x1' = x1 + sum_b Z_b T_b,   Z_b = mu^2 K^-1 B_b^T s_b,
// and B x1' = B x1 + sum_b (B Z_b) T_b: one back-substitution per dragged constraint when its drag
// starts, then only products with vectors. On a 64 x 64 sheet through 14 curves a
// back-substitution of the three coordinates is about 0.9 ms (its factor's 550 000 entries are
// read twice), more than a whole drag update may take.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <map>
#include <vector>

namespace varsurf {

class PenaltyDrag {
 public:
  // K^-1 r for the current factor.
  using Solve = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

  // Forgets the remembered step (a solve took more steps); the responses stay for its weight.
  void forget_step() { valid_ = false; }

  // Remembers a solve that stopped after its first step: its data d (rows x width), energy
  // right-hand side g, weight mu2, x1 and B x1. The responses are kept while mu2 stays (one
  // factor per weight: the samples do not change within a ConstrainedSolve).
  void remember(const Eigen::MatrixXd& d, const Eigen::MatrixXd& g, double mu2,
                const Eigen::MatrixXd& x1, const Eigen::MatrixXd& bx1);

  // The first step for data d, written to x and bx (B x), when the remembered step applies (same
  // g and mu2) and d differs from its data only by translations of at most kMaxBlocks blocks of
  // width-3 rows; false otherwise (x and bx untouched).
  // `solves` counts the responses computed (back-substitutions).
  bool first_step(const Eigen::MatrixXd& d, const Eigen::MatrixXd& g, double mu2,
                  const Eigen::SparseMatrix<double>& samples, const std::vector<int>& sample_block,
                  const std::vector<double>& sample_weight, const Solve& solve, Eigen::MatrixXd& x,
                  Eigen::MatrixXd& bx, int& solves);

  static constexpr size_t kMaxBlocks = 2;

 private:
  struct Response {
    Eigen::VectorXd z, bz;  // Z_b and B Z_b
  };
  const Response& response(int block, double mu2, const Eigen::SparseMatrix<double>& samples,
                           const std::vector<int>& sample_block,
                           const std::vector<double>& sample_weight, const Solve& solve);

  bool valid_ = false;
  Eigen::MatrixXd d_, g_, x1_, bx1_;
  double mu2_ = 0.0;
  std::map<int, Response> responses_;  // per block, for mu2_
};

}  // namespace varsurf
