// SPDX-License-Identifier: LGPL-2.1-or-later
#include "penalty_drag.hpp"

#include <algorithm>
#include <cmath>

namespace varsurf {

void PenaltyDrag::remember(const Eigen::MatrixXd& d, const Eigen::MatrixXd& g, double mu2,
                           const Eigen::MatrixXd& x1, const Eigen::MatrixXd& bx1) {
  if (mu2 != mu2_) responses_.clear();
  d_ = d;
  g_ = g;
  mu2_ = mu2;
  x1_ = x1;
  bx1_ = bx1;
  valid_ = true;
}

const PenaltyDrag::Response& PenaltyDrag::response(int block, double mu2,
                                                   const Eigen::SparseMatrix<double>& samples,
                                                   const std::vector<int>& sample_block,
                                                   const std::vector<double>& sample_weight,
                                                   const Solve& solve) {
  const auto found = responses_.find(block);
  if (found != responses_.end()) return found->second;
  Eigen::VectorXd s = Eigen::VectorXd::Zero(samples.rows());
  for (Eigen::Index r = 0; r < samples.rows(); ++r)
    if (sample_block[static_cast<size_t>(r)] == block)
      s(r) = std::sqrt(std::max(sample_weight[static_cast<size_t>(r)], 0.0));
  Response out;
  out.z = solve(mu2 * (samples.transpose() * s));
  out.bz = samples * out.z;
  return responses_.emplace(block, std::move(out)).first->second;
}

bool PenaltyDrag::first_step(const Eigen::MatrixXd& d, const Eigen::MatrixXd& g, double mu2,
                             const Eigen::SparseMatrix<double>& samples,
                             const std::vector<int>& sample_block,
                             const std::vector<double>& sample_weight, const Solve& solve,
                             Eigen::MatrixXd& x, Eigen::MatrixXd& bx, int& solves) {
  solves = 0;
  if (!valid_ || mu2 != mu2_ || d.cols() != 3 || d.rows() != d_.rows() || d.rows() == 0 ||
      g.rows() != g_.rows() || g.cols() != g_.cols() || g != g_)
    return false;
  // The blocks whose rows moved, each by one translation T_b of its rows' weights' roots.
  struct Moved {
    int block;
    Eigen::RowVector3d t;
  };
  std::vector<Moved> moved;
  const double size = std::max(d.cwiseAbs().maxCoeff(), d_.cwiseAbs().maxCoeff());
  const double rounding = 1e-13 * std::max(size, 1e-300);
  for (Eigen::Index r = 0; r < d.rows(); ++r) {
    const Eigen::RowVector3d delta = d.row(r) - d_.row(r);
    const int b = sample_block[static_cast<size_t>(r)];
    const double s = std::sqrt(std::max(sample_weight[static_cast<size_t>(r)], 0.0));
    auto it =
        std::find_if(moved.begin(), moved.end(), [&](const Moved& m) { return m.block == b; });
    if (it == moved.end()) {
      if (delta.cwiseAbs().maxCoeff() == 0.0) continue;
      if (moved.size() == kMaxBlocks) return false;
      // A block's rows are contiguous: its earlier rows did not move, so no common translation.
      if (r > 0 && sample_block[static_cast<size_t>(r - 1)] == b) return false;
      if (!(s > 0.0)) return false;
      moved.push_back({b, delta / s});
      continue;
    }
    if ((delta - s * it->t).cwiseAbs().maxCoeff() > rounding) return false;
  }
  if (moved.empty()) {
    x = x1_;
    bx = bx1_;
    return true;
  }
  Eigen::MatrixXd nx = x1_, nbx = bx1_;
  for (const Moved& m : moved) {
    solves += responses_.count(m.block) ? 0 : 1;
    const Response& z = response(m.block, mu2, samples, sample_block, sample_weight, solve);
    nx.noalias() += z.z * m.t;
    nbx.noalias() += z.bz * m.t;
  }
  x = std::move(nx);
  bx = std::move(nbx);
  return true;
}

}  // namespace varsurf
