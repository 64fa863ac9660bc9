#include "varsurf/core/sheet_solver.hpp"

#include <Eigen/SparseLU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "constraint_reduction.hpp"
#include "varsurf/core/errors.hpp"

namespace varsurf {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

void validate_problem(const SheetProblem& pb, const SolveOptions& opt) {
  pb.space.validate();
  if (pb.space.size() > opt.max_unknowns)
    throw InvalidInput("the sheet has " + std::to_string(pb.space.size()) +
                       " poles, more than the limit of " + std::to_string(opt.max_unknowns));
  if (pb.initial_poles.rows() != pb.space.size())
    throw InvalidInput("initial poles: expected " + std::to_string(pb.space.size()) +
                       " rows, got " + std::to_string(pb.initial_poles.rows()));
  if (!pb.initial_poles.allFinite()) throw InvalidInput("initial poles are not finite");
  for (int k : pb.fixed_poles)
    if (k < 0 || k >= pb.space.size()) throw InvalidInput("fixed pole index out of range");
  if (!(opt.regularization >= 0.0) || !std::isfinite(opt.regularization))
    throw InvalidInput("regularization must be a finite non-negative number");
  if (opt.refinement_steps < 0 || opt.refinement_steps > 20)
    throw InvalidInput("refinement steps must be in 0..20");
}

}  // namespace

SolveResult solve_sheet(const SheetProblem& pb, const SolveOptions& opt) {
  const auto start = Clock::now();
  validate_problem(pb, opt);
  SolveResult result;
  SolveReport& rep = result.report;

  // Unknowns: every pole not held fixed.
  const int total = pb.space.size();
  std::vector<int> free_index(static_cast<size_t>(total), 0);
  for (int k : pb.fixed_poles) free_index[static_cast<size_t>(k)] = -1;
  std::vector<int> free_poles;
  for (int k = 0; k < total; ++k)
    if (free_index[static_cast<size_t>(k)] == 0) {
      free_index[static_cast<size_t>(k)] = static_cast<int>(free_poles.size());
      free_poles.push_back(k);
    }
  const int n = static_cast<int>(free_poles.size());
  rep.unknowns = n;
  result.poles = pb.initial_poles;
  if (n == 0) {
    rep.total_seconds = seconds_since(start);
    return result;
  }

  auto t = Clock::now();
  const Eigen::SparseMatrix<double> h = assemble_thin_plate(pb.space, pb.energy);
  std::vector<ConstraintSamples> blocks;
  for (const PointConstraint& c : pb.points) blocks.push_back(sample_point(pb.space, c));
  for (size_t i = 0; i < pb.curves.size(); ++i) {
    try {
      blocks.push_back(sample_curve(pb.space, pb.curves[i]));
    } catch (const InvalidInput& e) {
      throw InvalidInput("curve " + std::to_string(i) + ": " + e.what());
    }
  }
  rep.assemble_seconds = seconds_since(t);

  t = Clock::now();
  const ReducedConstraints red = reduce_constraints(blocks, free_index, pb.initial_poles, n,
                                                    opt.rank_tolerance, opt.fit_tolerance);
  const int r = static_cast<int>(red.rows.rows());
  rep.constraint_samples = red.samples;
  rep.constraint_rank = r;
  rep.clusters = red.clusters;
  rep.conflict = red.conflict;
  rep.reduce_seconds = seconds_since(t);

  // KKT system [H_ff, A^T; A, 0] [p_f; y] = [-H_fc p_c; b] (Welch & Witkin eq. 9).
  t = Clock::now();
  double diag_mean = 0.0;
  for (int k : free_poles) diag_mean += h.coeff(k, k);
  diag_mean /= n;
  const double eps = opt.regularization * (diag_mean > 0.0 ? diag_mean : 1.0);

  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(h.nonZeros() + 2 * red.rows.nonZeros() + n));
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(n + r, 3);
  for (int col = 0; col < h.outerSize(); ++col) {
    const int fc = free_index[static_cast<size_t>(col)];
    for (Eigen::SparseMatrix<double>::InnerIterator it(h, col); it; ++it) {
      const int fr = free_index[static_cast<size_t>(it.row())];
      if (fr < 0) continue;
      if (fc >= 0)
        trip.emplace_back(fr, fc, it.value());
      else
        rhs.row(fr) -= it.value() * pb.initial_poles.row(col);
    }
  }
  for (int row = 0; row < r; ++row) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(red.rows, row); it; ++it) {
      trip.emplace_back(n + row, static_cast<int>(it.col()), it.value());
      trip.emplace_back(static_cast<int>(it.col()), n + row, it.value());
    }
  }
  rhs.bottomRows(r) = red.rhs;
  Eigen::SparseMatrix<double> kkt(n + r, n + r);
  kkt.setFromTriplets(trip.begin(), trip.end());
  kkt.makeCompressed();
  // The factored matrix carries eps on the unknowns' diagonal so that directions neither energy
  // nor constraints determine stay where they started; refinement against the exact matrix then
  // removes the eps bias from every determined direction (a proximal-point iteration).
  Eigen::SparseMatrix<double> shifted = kkt;
  for (int i = 0; i < n; ++i) shifted.coeffRef(i, i) += eps;

  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  lu.analyzePattern(shifted);
  lu.factorize(shifted);
  if (lu.info() != Eigen::Success)
    throw SolveFailure("the constrained system is singular: " + lu.lastErrorMessage());
  rep.factor_seconds = seconds_since(t);

  // One factorization serves x, y and z; iterative refinement recovers the digits the
  // indefinite factorization may lose.
  t = Clock::now();
  Eigen::MatrixX3d shifted_rhs = rhs;
  for (int i = 0; i < n; ++i)
    shifted_rhs.row(i) += eps * pb.initial_poles.row(free_poles[static_cast<size_t>(i)]);
  Eigen::MatrixX3d x = lu.solve(shifted_rhs);
  const double rhs_norm = std::max(rhs.norm(), 1e-300);
  for (int step = 0; step < opt.refinement_steps; ++step) {
    const Eigen::MatrixX3d res = rhs - kkt * x;
    if (!(res.norm() > 1e-15 * rhs_norm)) break;
    x += lu.solve(res);
  }
  if (!x.allFinite()) throw SolveFailure("the solve produced non-finite poles");
  rep.kkt_residual = (rhs - kkt * x).norm() / rhs_norm;
  if (r > 0) rep.constraint_residual = (red.rows * x.topRows(n) - red.rhs).cwiseAbs().maxCoeff();
  for (int i = 0; i < n; ++i) result.poles.row(free_poles[static_cast<size_t>(i)]) = x.row(i);
  rep.solve_seconds = seconds_since(t);
  rep.total_seconds = seconds_since(start);
  return result;
}

}  // namespace varsurf
