// SPDX-License-Identifier: LGPL-2.1-or-later
#include "region_solver.hpp"

#include <algorithm>
#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf {

using Sparse = Eigen::SparseMatrix<double>;

namespace {

// Whether a factorization of `matrix` is sound: it reports success and a right-hand side reaching
// every direction comes back (to `tolerance`, relative) through it. Sparse factorizations of
// singular systems can report success and answer garbage.
template <class Solver>
bool solves_back(const Solver& solver, const Sparse& matrix, double tolerance) {
  if (solver.info() != Eigen::Success) return false;
  const Eigen::Index n = matrix.rows();
  const Eigen::VectorXd probe =
      Eigen::VectorXd::LinSpaced(n, 1.0, 2.0)
          .cwiseProduct(Eigen::VectorXd::LinSpaced(n, 0.0, 37.0).array().sin().matrix());
  const Eigen::VectorXd back = solver.solve(probe);
  return back.allFinite() && (matrix * back - probe).norm() <= tolerance * probe.norm();
}

}  // namespace

RegionSolver::RegionSolver(const Sparse& h, const Sparse& a, const DetailEditOptions& options,
                           int level)
    : options_(options), h_(h), a_(a) {
  const Eigen::Index f = a.cols(), m = a.rows();
  if (options.solve != DetailSolve::direct) {
    // The masks' least-norm move A^T (A A^T)^-1 c: A A^T is sparse (masks overlap only near
    // each other), so a sparse factorization, checked by a probe as the KKT's below; dependent
    // masks (a curve's vertices at a coarse level) fall back to a dense complete orthogonal
    // decomposition, which takes them in least norm.
    const Sparse aat = Sparse(a * a.transpose());
    sparse_masks_.compute(aat);
    if (m > 0 && !solves_back(sparse_masks_, aat, 1e-10)) {
      dense_a_ = Eigen::MatrixXd(a);
      masks_.compute(dense_a_ * dense_a_.transpose());
      dense_masks_ = true;
    }
    if (options.solve == DetailSolve::sor) {
      std::vector<char> masked(static_cast<size_t>(f), 0);
      for (int outer = 0; outer < a.outerSize(); ++outer)
        for (Sparse::InnerIterator it(a, outer); it; ++it)
          if (it.value() != 0.0) masked[static_cast<size_t>(it.col())] = 1;
      for (Eigen::Index c = 0; c < f; ++c)
        if (!masked[static_cast<size_t>(c)]) relaxed_.push_back(c);
    }
    return;
  }
  std::vector<Eigen::Triplet<double>> k_entries;
  double diagonal = 0.0;
  for (Eigen::Index i = 0; i < f; ++i) diagonal = std::max(diagonal, h.coeff(i, i));
  // The energy scaled to a largest diagonal of 1 (the minimizer is the same): its bend terms go
  // as the model's size to the -4, the constraints' rows do not, and the check of the
  // factorization below must not depend on the model's size.
  const double scale = diagonal > 0.0 ? 1.0 / diagonal : 1.0;
  for (int outer = 0; outer < h.outerSize(); ++outer)
    for (Sparse::InnerIterator it(h, outer); it; ++it)
      k_entries.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()),
                             scale * it.value());
  diagonal = 1.0;
  // A whisker on the diagonal: a region that the constraints leave free to translate (the energy
  // of a translation is zero) then takes the smallest move.
  for (Eigen::Index i = 0; i < f; ++i)
    k_entries.emplace_back(static_cast<int>(i), static_cast<int>(i), 1e-12 * diagonal);
  const size_t energy_entries = k_entries.size();
  for (int outer = 0; outer < a.outerSize(); ++outer)
    for (Sparse::InnerIterator it(a, outer); it; ++it) {
      k_entries.emplace_back(static_cast<int>(f + it.row()), static_cast<int>(it.col()),
                             it.value());
      k_entries.emplace_back(static_cast<int>(it.col()), static_cast<int>(f + it.row()),
                             it.value());
    }
  Sparse k(f + m, f + m);
  k.setFromTriplets(k_entries.begin(), k_entries.end());
  kkt_.compute(k);
  // SparseLU factors some singular KKT systems (dependent masks, as the vertices along a curve
  // give a coarse level) without a word, and its answer then swings the region by 1e5 times the
  // model (measured).
  if (solves_back(kkt_, k, 1e-8)) return;
  // More constraints than this level can meet (their masks dependent): their least-squares fit,
  // the energy keeping it smooth; the finer levels then meet them.
  Sparse h_ff(f, f);
  h_ff.setFromTriplets(k_entries.begin(),
                       k_entries.begin() + static_cast<std::ptrdiff_t>(energy_entries));
  const Sparse ata = Sparse(a.transpose() * a);
  double ata_diagonal = 0.0;
  for (Eigen::Index i = 0; i < f; ++i) ata_diagonal = std::max(ata_diagonal, ata.coeff(i, i));
  penalty_weight_ = 1e6 * std::max(diagonal, 1e-300) / std::max(ata_diagonal, 1e-300);
  penalty_.compute(Sparse(h_ff + penalty_weight_ * ata));
  if (penalty_.info() != Eigen::Success)
    throw InvalidInput("the constraints solved at level " + std::to_string(level) +
                       " cannot be met: remove some or solve them at a finer level");
  least_squares_ = true;
}

Eigen::MatrixXd RegionSolver::solve(const Eigen::MatrixXd& c, double stop, int& sweeps) const {
  const Eigen::Index f = a_.cols(), m = a_.rows();
  if (options_.solve == DetailSolve::direct && least_squares_)
    return penalty_.solve(Eigen::MatrixXd(penalty_weight_ * (a_.transpose() * c)));
  if (options_.solve == DetailSolve::direct) {
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(f + m, c.cols());
    rhs.bottomRows(m) = c;
    return kkt_.solve(rhs).topRows(f);
  }
  Eigen::MatrixXd x = dense_masks_ ? Eigen::MatrixXd(dense_a_.transpose() * masks_.solve(c))
                                   : Eigen::MatrixXd(a_.transpose() * sparse_masks_.solve(c));
  if (options_.solve != DetailSolve::sor) return x;
  // Gauss-Seidel with over-relaxation on the rest of the region (the paper's sec. 4.3); the
  // unknowns outside the region stand still.
  for (int sweep = 0; sweep < options_.max_sweeps; ++sweep) {
    ++sweeps;
    double change = 0.0;
    for (const Eigen::Index i : relaxed_) {
      Eigen::RowVectorXd sum = Eigen::RowVectorXd::Zero(x.cols());
      double diagonal = 0.0;
      for (Sparse::InnerIterator it(h_, i); it; ++it) {
        if (it.row() == i)
          diagonal = it.value();
        else
          sum += it.value() * x.row(it.row());
      }
      if (diagonal <= 0.0) continue;
      const Eigen::RowVectorXd next =
          (1.0 - options_.omega) * x.row(i) - (options_.omega / diagonal) * sum;
      change = std::max(change, (next - x.row(i)).norm());
      x.row(i) = next;
    }
    if (change <= stop) break;
  }
  return x;
}

}  // namespace varsurf
