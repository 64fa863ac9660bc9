// SPDX-License-Identifier: LGPL-2.1-or-later
#include "constrained_solve.hpp"

#include <Eigen/SparseCholesky>
#ifdef VARSURF_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>

#include "serial_openmp.hpp"
#endif
#ifdef VARSURF_HAVE_SPQR
#include <Eigen/SPQRSupport>
#endif
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "factor_correction.hpp"
#include "free_block.hpp"
#include "penalty_drag.hpp"
#include "solve_limits.hpp"
#include "stopwatch.hpp"
#include "varsurf/core/errors.hpp"

namespace varsurf {

namespace {

using Sparse = Eigen::SparseMatrix<double>;
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// change(): an earlier factor serves at most this many added sample rows (one back-substitution
// each when the correction is set up), and a weight within kMaxWeightDrift of its own (the
// correction's conjugate gradients need about 7 steps at 5 %, 10 at 25 %).
constexpr Eigen::Index kMaxAddedRows = 16;
constexpr double kMaxWeightDrift = 0.25;

// Penalty steps before SolveOptions::give_up_early judges the rate: the first ones fall fast.
constexpr int kWarmUpSteps = 20;
// The penalty refinement restarts on a heavier weight when the slowest constraint still needs
// more than kStepBudget steps at its rate, chosen to make that rate kTargetRate (at most
// SolveOptions::max_weight_gain times the configured weight). Benchmark 2's sheets at 1e-3 (3 and
// 6 interior curves), with a gain of up to 30: 193 and 61 steps became 18 and 7 with the bending
// energy -0.7 % and +1.2 %. A target rate of 0.3 cost +4.5 % energy, and continuing the
// refinement on the raised weight instead of restarting it (the method of multipliers with a
// growing penalty) threw the 6-curve sheet off (energy x 300) through a sample the sheet cannot
// reach.
constexpr double kStepBudget = 8.0;
constexpr double kTargetRate = 0.5;
constexpr size_t kRateSpan = 4;

}  // namespace

void check_keep_going(const SolveOptions& options) {
  if (options.keep_going && !options.keep_going()) throw Cancelled("the solve was cancelled");
  check_deadline();
}

const char* to_string(SolveMode mode) {
  switch (mode) {
    case SolveMode::automatic:
      return "automatic";
    case SolveMode::exact:
      return "exact";
    case SolveMode::penalty:
      return "penalty";
    case SolveMode::cg:
      return "cg";
    case SolveMode::tsvd:
      return "tsvd";
    case SolveMode::mtsvd:
      return "mtsvd";
    case SolveMode::multigrid:
      return "multigrid";
  }
  return "unknown";
}

struct ConstrainedSolve::Impl {
  SolveOptions opt;
  SolveMode mode = SolveMode::exact;
  Eigen::MatrixXd shift;  // the rest shape (all columns), or empty: unknowns are x - shift
  // The start is the energy's unconstrained minimum: constraints it meets are held, not fitted.
  bool start_is_minimum = false;
  std::vector<int> free_cols, free_index;
  int n = 0, r = 0;
  Eigen::Index width = 1;
  Eigen::MatrixXd x0;        // all columns
  Eigen::MatrixXd x0_free;   // n x width
  Eigen::MatrixXd coupling;  // Q_fc x_c, n x width
  ReducedConstraints red;
  Sparse a;     // r x n, orthonormal rows
  Sparse q_ff;  // n x n
  double eps = 0.0;
  // exact, mtsvd
  Sparse kkt;
  Eigen::SparseLU<Sparse, Eigen::COLAMDOrdering<int>> lu;
  // Without constraint rows the KKT matrix is the energy alone, symmetric and (with eps)
  // positive definite: a Cholesky factor instead of the LU (measured on a 67 x 67 PDE sheet held
  // by its fixed poles: the LU took 295 ms, this 59 ms; at 259 x 259 about 20 s and 1.4 s).
  bool kkt_spd = false;
#ifdef VARSURF_HAVE_CHOLMOD
  Eigen::CholmodDecomposition<Sparse> kkt_ldlt;
#else
  Eigen::SimplicialLDLT<Sparse> kkt_ldlt;
#endif
  // penalty: the raw samples (no reduction), one sparse Cholesky of Q + mu^2 B^T B. A solve
  // that converges slowly raises mu^2 and refactors (same pattern, numeric only); the raised
  // weight and its factor stay for the next solves (drags), hence mutable.
  mutable Sparse btb;  // B^T B, formed when a factorization needs it
  mutable double mu2 = 0.0;
  mutable double first_mu2 = 0.0;     // mu^2 before any raise
  mutable double heaviest_mu2 = 0.0;  // the largest mu^2 a raise may reach
  // The factor of Q + weight B_f^T B_f + eps I; shared with a later solve of the same energy that
  // adds constraints (change()), which refactors into a factor of its own.
  struct Factor {
    Eigen::SimplicialLDLT<Sparse> ldlt;
#ifdef VARSURF_HAVE_CHOLMOD
    // CHOLMOD beyond 500 unknowns, on one OpenMP thread (measured on benchmark 3's sheets,
    // factor and drag update against SimplicialLDLT: 24 x 24 poles 4.1 / 0.65 ms against
    // 4.9 / 0.71 ms, 45 x 45 13 / 1.2 ms against 19 / 1.8 ms, 64 x 64 30 / 2.2 ms against
    // 52 / 3.8 ms); at 16 x 16 the two are even.
    Eigen::CholmodDecomposition<Sparse> cholmod;
    bool use_cholmod = false;
#endif
    double weight = 0.0, eps = 0.0;
    double seconds = 0.0;                   // what its factorization took
    std::shared_ptr<const RowSparse> rows;  // B_f
    Eigen::MatrixXd solve(const Eigen::MatrixXd& r) const {
#ifdef VARSURF_HAVE_CHOLMOD
      if (use_cholmod) return cholmod.solve(r);
#endif
      return ldlt.solve(r);
    }
  };
  mutable std::shared_ptr<Factor> factor;
  // Set when `factor` is an earlier solve's, made for fewer sample rows: see FactorCorrection.
  mutable std::unique_ptr<FactorCorrection> correction;
  mutable int extra_substitutions = 0;  // the correction's, beyond one per factor_solve
  // The time the correction took; once it exceeds the factor's own, a new factorization is
  // cheaper (a refinement of many steps pays the correction's iterations at each).
  mutable double correction_seconds = 0.0;
  // B by rows, shared with the factor rather than copied (Eigen 3.4's sparse matrices have no
  // move assignment).
  std::shared_ptr<const RowSparse> sample_rows;
  // Takes the factor of an earlier solve of the same energy whose samples are this one's with
  // at most kMaxAddedRows rows removed, under a weight close to this one's.
  bool borrow_factor(const Impl& earlier);
  // (Q + mu^2 B^T B + eps I) v, without forming the matrix.
  Eigen::MatrixXd apply_penalty(const Eigen::MatrixXd& v) const {
    Eigen::MatrixXd out = q_ff * v;
    out.noalias() += mu2 * (samples.transpose() * (samples * v));
    return out + eps * v;
  }
#ifdef VARSURF_HAVE_SPQR
  // penalty_qr: W&W's eq. 10 as written, the stacked system (mu B; S) factored by SuiteSparseQR,
  // S^T S = Q + eps I from a sparse Cholesky of the energy alone.
  mutable Eigen::SPQR<Sparse> spqr;
  Eigen::SimplicialLLT<Sparse> energy_factor;
  bool use_qr = false;
#endif
  // One penalty step: argmin x^T (Q + eps I) x - 2 g^T x + mu^2 |B x - d|^2.
  Eigen::MatrixXd penalty_step(const Eigen::MatrixXd& g, const Eigen::MatrixXd& d) const {
#ifdef VARSURF_HAVE_SPQR
    if (use_qr) {
      // S^T s = g: s = L^-1 P g for P (Q + eps I) P^T = L L^T, S = L^T P.
      const Eigen::MatrixXd s_rhs =
          energy_factor.matrixL().solve(Eigen::MatrixXd(energy_factor.permutationP() * g));
      Eigen::MatrixXd stacked(samples.rows() + n, width);
      stacked.topRows(samples.rows()) = std::sqrt(mu2) * d;
      stacked.bottomRows(n) = s_rhs;
      // Eigen's SPQR wrapper solves one right-hand side at a time (it asserts on more).
      Eigen::MatrixXd x(n, width);
      for (Eigen::Index c = 0; c < width; ++c)
        x.col(c) = spqr.solve(Eigen::VectorXd(stacked.col(c)));
      return x;
    }
#endif
    Eigen::MatrixXd rhs = g;
    if (samples.rows() > 0) rhs += mu2 * (samples.transpose() * d);
    return factor_solve(rhs);
  }
  Sparse samples;                     // B: sample rows x n
  Eigen::MatrixXd sample_rhs;         // D: sample rows x width (fixed columns moved over)
  std::vector<int> sample_block;      // block of each sample row
  std::vector<double> sample_weight;  // w of each sample row (coupled rows: per coordinate)
  std::vector<double> block_weight;   // sum of the sample weights of each block
  std::vector<bool> block_exact;
  mutable Eigen::MatrixXd bregman_offset;  // d_k - D of the last solve: a warm start for drags
  mutable PenaltyDrag drag;                // drags of whole constraints without a back-substitution
  mutable Eigen::MatrixXd last_bx;         // B x of the last penalty solve
  // Added to D in each solve: for a constraint the start already meets within the tolerance it
  // is B x0 - D of the prepared data, so the sheet keeps the start there and follows only the
  // data's later motion (its noise below the tolerance is not fitted).
  Eigen::MatrixXd sample_offset;
  int held_blocks = 0;
  // cg
  Eigen::VectorXd inv_diag;
  // tsvd / mtsvd on large constraint groups: CGLS iterations as the regularizing truncation
  bool krylov = false;
  Eigen::MatrixXd solve_krylov(const Eigen::MatrixXd& g, const Eigen::MatrixXd& d,
                               SolveReport& rep) const;

  Eigen::MatrixXd energy_rhs(const Eigen::MatrixXd& f) const {  // f_f - Q_fc x_c
    Eigen::MatrixXd out(n, width);
    for (int i = 0; i < n; ++i) out.row(i) = f.row(free_cols[static_cast<size_t>(i)]);
    return out - coupling;
  }
  Eigen::VectorXd project(const Eigen::VectorXd& v) const {  // onto null(A): A has orthonormal rows
    return r > 0 ? Eigen::VectorXd(v - a.transpose() * (a * v)) : v;
  }
  Eigen::MatrixXd solve_kkt(const Eigen::MatrixXd& g, const Eigen::MatrixXd& b,
                            SolveReport& rep) const;
  Eigen::MatrixXd solve_penalty(const Eigen::MatrixXd& g, const Eigen::MatrixXd& d,
                                SolveReport& rep) const;
  // Where a refinement stood after a step: a run resumes from it.
  struct Progress {
    Eigen::MatrixXd x, dk;
    std::vector<double> previous, previous_excess, excess_history;
    int it = 0;
  };
  // One run of the penalty refinement from data d_k (may_raise: it may restart on a heavier
  // weight).
  struct Refined {
    Eigen::MatrixXd x, dk, bx;  // bx: B x
    bool met = true;            // every constraint done (exact ones converged)
    bool tolerance_met = true;  // every toleranced constraint within it
    double worst = 0.0;         // the largest block RMS
    int steps = 0;
    // The run on the configured weight when it first restarted on a heavier one (null: no raise).
    std::shared_ptr<const Progress> before_raise;
  };
  // resume: continue that run's steps (on the weight it ran on) instead of starting from dk.
  Refined refine(const Eigen::MatrixXd& g, const Eigen::MatrixXd& d, Eigen::MatrixXd dk,
                 bool may_raise, const Progress* resume = nullptr) const;
  // K^-1 r for the penalty matrix's factor (not the QR form).
  Eigen::MatrixXd factor_solve(const Eigen::MatrixXd& r) const;
  // Per constraint block: its rows' summed squared residual and its farthest sample's distance.
  void block_residuals(const Eigen::MatrixXd& res, std::vector<double>& sq,
                       std::vector<double>& far) const;
  // A block within fit_tolerance as the refinement judges it: RMS, and no sample beyond
  // max_fit_factor times it.
  bool within(size_t block, double sq, double far) const {
    const double rms = block_weight[block] > 0.0 ? std::sqrt(sq / block_weight[block]) : 0.0;
    return rms <= opt.fit_tolerance && far <= opt.max_fit_factor * opt.fit_tolerance;
  }
  // A block the refinement may stop on: toleranced (not exact) and within its tolerance.
  bool done(size_t block, double sq, double far) const {
    return !block_exact[block] && opt.fit_tolerance > 0.0 && within(block, sq, far);
  }
  void setup_samples(const std::vector<ConstraintSamples>& blocks);
  // The blocks' right-hand sides relative to the rest shape (empty without one).
  std::vector<ConstraintSamples> shifted(const std::vector<ConstraintSamples>& blocks) const;
  void reduce(const std::vector<ConstraintSamples>& blocks, SolveReport& rep);
  void factor_kkt();
  // false if the penalty matrix is not numerically positive definite at this eps. `earlier`: a
  // solve of the same energy whose factor may serve (see borrow_factor), or null.
  bool factor_penalty(double scale, const Impl* earlier);
  // Raises mu^2 (and refactors) so that a mode converging at `rate` a step converges at
  // kTargetRate; false if it keeps the weight (no room left, or the factorization failed).
  bool raise_weight(double rate) const;
  // Factors Q + weight B^T B + eps I (analyze: also its ordering, and the choice of CHOLMOD);
  // false if it is not numerically positive definite.
  bool factor_numeric(double weight, bool analyze) const;
  // Refactors on `weight` and makes it mu^2; false if that fails, with the factor of the
  // current mu^2 restored.
  bool refactor(double weight) const;
  // The samples' right-hand sides with fixed columns moved over (and the rest shape taken off
  // with minus_shift, for blocks not yet shifted).
  Eigen::MatrixXd samples_rhs(const std::vector<ConstraintSamples>& blocks,
                              bool minus_shift = false) const;
  // rhs -= the rest shape's value of sample row r of `block` (shifted() and samples_rhs).
  void take_off_shift(const ConstraintSamples& block, int r, Eigen::RowVectorXd& rhs) const {
    const auto& idx = block.index[static_cast<size_t>(r)];
    const Eigen::VectorXd& c = block.coeff[static_cast<size_t>(r)];
    for (size_t k = 0; k < idx.size(); ++k) {
      if (idx[k] < 0 || idx[k] >= shift.rows())
        throw InvalidInput("constraint sample index out of range");
      rhs -= c(static_cast<Eigen::Index>(k)) * shift.row(idx[k]);
    }
  }
  Eigen::MatrixXd solve_cg(const Eigen::MatrixXd& g, const Eigen::MatrixXd& b,
                           SolveReport& rep) const;
};

ConstrainedSolve::ConstrainedSolve(const Quadratic& pb, const SolveOptions& opt, SolveReport& rep,
                                   const ConstrainedSolve* earlier)
    : impl_(new Impl) {
  if (opt.mode == SolveMode::multigrid)
    throw InvalidInput(
        "multigrid solves a single sheet held by its fixed poles alone (solve_sheet); choose "
        "another solve mode for constraints, joined sheets, refinement and drags");
  Impl& m = *impl_;
  m.opt = opt;
  const int total = static_cast<int>(pb.q.rows());
  m.width = pb.x0.cols();
  m.x0 = pb.x0;
  if (pb.rest.size()) {
    if (pb.rest.rows() != pb.x0.rows() || pb.rest.cols() != pb.x0.cols() || !pb.rest.allFinite())
      throw InvalidInput("rest shape: expected finite values shaped like the start");
    // Everything below works on the displacement from the rest shape.
    m.shift = pb.rest;
    m.x0 = pb.x0 - pb.rest;
  }
  const std::vector<ConstraintSamples> shifted = m.shifted(pb.blocks);
  const std::vector<ConstraintSamples>& blocks = m.shift.size() ? shifted : pb.blocks;
  {
    FreeUnknowns f = free_unknowns(pb.fixed);
    m.free_index = std::move(f.slot);
    m.free_cols = std::move(f.free);
  }
  m.n = static_cast<int>(m.free_cols.size());
  rep.unknowns = m.n;

  // The mode, before the reduction (the L-curve modes truncate differently).
  m.mode = opt.mode;
  if (m.mode == SolveMode::automatic) {
    const int cluster = m.n > 0 ? largest_cluster(blocks, m.free_index, m.n) : 0;
    if (m.n > opt.direct_limit) {
      m.mode = SolveMode::cg;
      rep.mode_reason = "cg: " + std::to_string(m.n) + " unknowns, more than the " +
                        std::to_string(opt.direct_limit) + " factored directly";
    } else if (cluster > opt.cluster_limit && opt.fit_tolerance > 0.0 &&
               std::none_of(blocks.begin(), blocks.end(),
                            [](const ConstraintSamples& b) { return b.exact; })) {
      m.mode = SolveMode::penalty;
      rep.mode_reason = "penalty: the largest group of interacting constraints has " +
                        std::to_string(cluster) + " unknowns (more than " +
                        std::to_string(opt.cluster_limit) +
                        "), too many for the exact mode's dense reduction";
    } else {
      m.mode = SolveMode::exact;
      rep.mode_reason = "exact: " + std::to_string(m.n) +
                        " unknowns, constraint groups of at most " + std::to_string(cluster) +
                        ", sparse KKT factorization";
    }
  } else {
    rep.mode_reason = std::string(to_string(m.mode)) + ": chosen";
  }
  rep.mode = m.mode;
  if (m.n == 0) return;
  // Row width of one coordinate's energy (a coupled system, width 1, holds three per pole).
  const long long row = (pb.q.nonZeros() + total - 1) / std::max(total, 1) / (m.width == 1 ? 3 : 1);
  check_memory(m.n, std::max(row, 1LL), m.mode, opt, "the solve");

  // The energy on the free columns, and its coupling to the fixed ones.
  auto t = Clock::now();
  m.x0_free.resize(m.n, m.width);
  for (int i = 0; i < m.n; ++i) m.x0_free.row(i) = m.x0.row(m.free_cols[static_cast<size_t>(i)]);
  m.q_ff = free_block(pb.q, FreeUnknowns{m.free_index, m.free_cols});
  // Q_fc x_c: the energy's pull from the held columns.
  m.coupling = Eigen::MatrixXd::Zero(m.n, m.width);
  for (int col = 0; col < pb.q.outerSize(); ++col) {
    if (m.free_index[static_cast<size_t>(col)] >= 0) continue;
    for (Sparse::InnerIterator it(pb.q, col); it; ++it) {
      const int fr = m.free_index[static_cast<size_t>(it.row())];
      if (fr >= 0) m.coupling.row(fr) += it.value() * m.x0.row(col);
    }
  }
  double diag_mean = m.q_ff.diagonal().sum();
  diag_mean /= m.n;
  if (!std::isfinite(diag_mean))
    throw SolveFailure("the energy matrix is not finite (poles or weights too large)");
  const double scale = diag_mean > 0.0 ? diag_mean : 1.0;
  m.eps = opt.regularization * scale;
  // Is the start the energy's unconstrained minimum (a rest shape with nothing else pulling)? Then
  // its residual is what the discrepancy principle measures: constraints it already meets
  // within the tolerance ask nothing of the sheet.
  {
    const Eigen::MatrixXd g = m.energy_rhs(pb.f);
    const double gradient = (m.q_ff * m.x0_free - g).cwiseAbs().maxCoeff();
    const double size = scale * m.x0_free.cwiseAbs().maxCoeff() + g.cwiseAbs().maxCoeff();
    m.start_is_minimum = gradient <= 1e-12 * size;
  }
  const double assemble_seconds = seconds_since(t);

  t = Clock::now();
  if ((m.mode == SolveMode::tsvd || m.mode == SolveMode::mtsvd) &&
      largest_cluster(blocks, m.free_index, m.n) > opt.krylov_limit) {
    m.krylov = true;
    rep.mode_reason +=
        " (Krylov: CGLS iterations truncated at the L-curve corner; the largest "
        "constraint group exceeds " +
        std::to_string(opt.krylov_limit) + " unknowns for a dense SVD)";
  }
  if (m.mode == SolveMode::penalty || m.krylov) {
    m.setup_samples(blocks);
    rep.constraint_samples = static_cast<int>(m.samples.rows());
    rep.held_constraints = m.held_blocks;
  } else {
    m.reduce(blocks, rep);
  }
  rep.reduce_seconds = seconds_since(t);

  check_keep_going(opt);  // the reduction can be long; the factorization cannot be interrupted
  t = Clock::now();
  if (m.krylov && m.mode == SolveMode::tsvd) {
    // CGLS needs no factorization.
  } else if ((m.mode == SolveMode::exact || m.mode == SolveMode::mtsvd) && !m.krylov) {
    m.factor_kkt();
  } else if (m.mode == SolveMode::penalty || m.krylov) {
    if (!(opt.penalty_weight > 0.0) || !std::isfinite(opt.penalty_weight))
      throw InvalidInput("penalty weight must be a positive number");
    if (opt.penalty_steps < 1) throw InvalidInput("penalty steps must be at least 1");
    if (!(opt.max_weight_gain >= 1.0) || !std::isfinite(opt.max_weight_gain))
      throw InvalidInput("the penalty weight's largest gain must be finite and at least 1");
    // Rounding can leave the penalty matrix of a badly scaled energy (high degree, thin faces)
    // short of positive definite by more than the regularization: a larger pull toward the
    // previous iterate (the refinement is a proximal iteration, so it biases nothing) restores
    // it; if even that fails, the exact mode's LU takes the semi-definite system.
    const double first_eps = m.eps;
    bool factored = m.factor_penalty(scale, earlier ? earlier->impl_.get() : nullptr);
    // eps must grow each step: an energy scale near the smallest double underflows it to 0.
    for (double eps = std::max(first_eps, 1e-13 * scale) * 1e3;
         !factored && eps > 0.0 && std::isfinite(eps) && eps <= 1e-4 * scale * (1.0 + 1e-9);
         eps *= 1e3) {
      m.eps = eps;
      factored = m.factor_penalty(scale, earlier ? earlier->impl_.get() : nullptr);
    }
    if (factored && m.eps != first_eps) {
      std::ostringstream why;
      why << "; the penalty system was not positive definite, regularized with " << m.eps / scale
          << " of the energy's scale";
      rep.mode_reason += why.str();
    } else if (!factored && m.krylov) {
      throw SolveFailure(
          "the penalty system could not be factored (not positive definite even when "
          "regularized)");
    } else if (!factored) {
      m.eps = first_eps;
      m.mode = SolveMode::exact;
      rep.mode = m.mode;
      rep.mode_reason +=
          "; the penalty system was not positive definite even when regularized: solved by the "
          "exact mode instead";
      m.reduce(blocks, rep);
      m.factor_kkt();
    }
  } else if (m.mode == SolveMode::cg) {
    m.inv_diag.resize(m.n);
    for (int i = 0; i < m.n; ++i) {
      const double d = m.q_ff.coeff(i, i) + m.eps;
      m.inv_diag(i) = d > 0.0 ? 1.0 / d : 1.0;
    }
  }
  rep.factor_seconds = seconds_since(t) + assemble_seconds;
}

std::vector<ConstraintSamples> ConstrainedSolve::Impl::shifted(
    const std::vector<ConstraintSamples>& blocks) const {
  if (!shift.size()) return {};
  std::vector<ConstraintSamples> out = blocks;
  for (ConstraintSamples& block : out)
    for (int r = 0; r < block.rows(); ++r) {
      if (block.rhs.cols() != width) throw InvalidInput("constraint samples of mixed widths");
      Eigen::RowVectorXd rhs = block.rhs.row(r);
      take_off_shift(block, r, rhs);
      block.rhs.row(r) = rhs;
    }
  return out;
}

void ConstrainedSolve::Impl::reduce(const std::vector<ConstraintSamples>& blocks,
                                    SolveReport& rep) {
  ReductionOptions ro;
  ro.rank_tolerance = opt.rank_tolerance;
  ro.fit_tolerance = opt.fit_tolerance;
  ro.keep_tolerance = opt.keep_tolerance;
  ro.max_fit_factor = opt.max_fit_factor;
  ro.start_is_minimum = start_is_minimum;
  ro.truncation = (mode == SolveMode::tsvd || mode == SolveMode::mtsvd) ? Truncation::lcurve
                                                                        : Truncation::discrepancy;
  red = reduce_constraints(blocks, free_index, x0, n, ro);
  r = static_cast<int>(red.rows.rows());
  a = red.rows;
  rep.constraint_samples = red.samples;
  rep.constraint_rank = r;
  rep.clusters = red.clusters;
  rep.held_constraints = red.held;
  rep.conflict = red.conflict;
  rep.lcurve = red.lcurve;
}

void ConstrainedSolve::Impl::factor_kkt() {
  // KKT system [Q_ff, A^T; A, 0] [x_f; y] = [f_f - Q_fc x_c; b] (Welch & Witkin eq. 9).
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(q_ff.nonZeros() + 2 * red.rows.nonZeros()));
  for (int col = 0; col < q_ff.outerSize(); ++col)
    for (Sparse::InnerIterator it(q_ff, col); it; ++it)
      trip.emplace_back(static_cast<int>(it.row()), col, it.value());
  for (int row = 0; row < r; ++row)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(red.rows, row); it; ++it) {
      trip.emplace_back(n + row, static_cast<int>(it.col()), it.value());
      trip.emplace_back(static_cast<int>(it.col()), n + row, it.value());
    }
  kkt.resize(n + r, n + r);
  kkt.setFromTriplets(trip.begin(), trip.end());
  kkt.makeCompressed();
  // The factored matrix carries eps on the unknowns' diagonal so that directions neither
  // energy nor constraints determine stay where they started; refinement against the exact
  // matrix then removes the eps bias from every determined direction (a proximal iteration).
  Sparse shifted_kkt = kkt;
  for (int i = 0; i < n; ++i) shifted_kkt.coeffRef(i, i) += eps;
  kkt_spd = r == 0;
  if (kkt_spd) {
    SerialOpenMp serial;
#ifdef VARSURF_HAVE_CHOLMOD
    kkt_ldlt.cholmod().nmethods = 1;  // AMD alone, as the penalty factor (see factor_penalty)
    kkt_ldlt.cholmod().method[0].ordering = CHOLMOD_AMD;
#endif
    kkt_ldlt.compute(shifted_kkt);
    if (kkt_ldlt.info() == Eigen::Success) return;
    kkt_spd = false;  // not numerically positive definite: the LU takes it
  }
  lu.analyzePattern(shifted_kkt);
  lu.factorize(shifted_kkt);
  if (lu.info() != Eigen::Success)
    throw SolveFailure("the constrained system is singular: " + lu.lastErrorMessage());
}

bool ConstrainedSolve::Impl::factor_penalty(double scale, const Impl* earlier) {
  // W&W eq. 10 minimizes |(mu B; H) p - (mu d; f)|; its normal equations (Q + mu^2 B^T B) p =
  // f + mu^2 B^T d keep the sparsity of Q (each sample row touches one span's poles), so a
  // sparse Cholesky replaces W&W's sparse QR of the stacked system, which would need a square
  // root of the energy. mu^2 is relative to the energy's and the samples' scales.
  // B^T B's diagonal: the columns' sums of squares (B^T B itself is formed only to factor).
  double btb_mean = 0.0;
  for (int col = 0; col < samples.outerSize(); ++col) {
    double sum = 0.0;
    for (Sparse::InnerIterator it(samples, col); it; ++it) sum += it.value() * it.value();
    btb_mean += sum;
  }
  btb_mean /= n;
  mu2 = opt.penalty_weight * scale / (btb_mean > 0.0 ? btb_mean : 1.0);
  if (opt.penalty_qr) {
#ifdef VARSURF_HAVE_SPQR
    Sparse q_eps = q_ff;
    for (int i = 0; i < n; ++i) q_eps.coeffRef(i, i) += eps;
    energy_factor.compute(q_eps);
    if (energy_factor.info() != Eigen::Success) return false;
    const Sparse root = Sparse(Sparse(energy_factor.matrixU()) * energy_factor.permutationP());
    std::vector<Eigen::Triplet<double>> st;
    const double mu = std::sqrt(mu2);
    for (int col = 0; col < samples.outerSize(); ++col)
      for (Sparse::InnerIterator it(samples, col); it; ++it)
        st.emplace_back(static_cast<int>(it.row()), col, mu * it.value());
    for (int col = 0; col < root.outerSize(); ++col)
      for (Sparse::InnerIterator it(root, col); it; ++it)
        st.emplace_back(static_cast<int>(samples.rows() + it.row()), col, it.value());
    Sparse stacked(samples.rows() + n, n);
    stacked.setFromTriplets(st.begin(), st.end());
    stacked.makeCompressed();
    spqr.compute(stacked);
    if (spqr.info() != Eigen::Success)
      throw SolveFailure("penalty (QR): SuiteSparseQR could not factor the stacked system");
    use_qr = true;
    return true;
#else
    throw InvalidInput("penalty_qr needs SuiteSparseQR, which this build does not have");
#endif
  }
  first_mu2 = mu2;
  heaviest_mu2 = opt.max_weight_gain * mu2;
  if (earlier && borrow_factor(*earlier)) return true;
  return factor_numeric(mu2, true);
}

bool ConstrainedSolve::Impl::borrow_factor(const Impl& earlier) {
  const std::shared_ptr<Factor>& f = earlier.factor;
  if (!f || mode != SolveMode::penalty || krylov || earlier.mode != SolveMode::penalty ||
      earlier.krylov || earlier.n != n || earlier.width != width ||
      earlier.free_cols != free_cols || f->eps != eps ||
      !(std::abs(mu2 / f->weight - 1.0) <= kMaxWeightDrift) || !f->rows || f->rows->cols() != n)
    return false;
#ifdef VARSURF_HAVE_SPQR
  if (earlier.use_qr) return false;
#endif
  // The same energy, entry for entry.
  const Sparse& q = earlier.q_ff;
  if (q.nonZeros() != q_ff.nonZeros() ||
      !std::equal(q.outerIndexPtr(), q.outerIndexPtr() + n + 1, q_ff.outerIndexPtr()) ||
      !std::equal(q.innerIndexPtr(), q.innerIndexPtr() + q.nonZeros(), q_ff.innerIndexPtr()) ||
      !std::equal(q.valuePtr(), q.valuePtr() + q.nonZeros(), q_ff.valuePtr()))
    return false;
  // The factor's rows, in order, among this solve's: the others are the added ones.
  const RowSparse& old_rows = *f->rows;
  const RowSparse& new_rows = *sample_rows;
  const auto same_row = [&](Eigen::Index i, Eigen::Index j) {
    const Eigen::Index a0 = old_rows.outerIndexPtr()[i], a1 = old_rows.outerIndexPtr()[i + 1];
    const Eigen::Index b0 = new_rows.outerIndexPtr()[j];
    return a1 - a0 == new_rows.outerIndexPtr()[j + 1] - b0 &&
           std::equal(old_rows.innerIndexPtr() + a0, old_rows.innerIndexPtr() + a1,
                      new_rows.innerIndexPtr() + b0) &&
           std::equal(old_rows.valuePtr() + a0, old_rows.valuePtr() + a1, new_rows.valuePtr() + b0);
  };
  std::vector<Eigen::Index> added;
  Eigen::Index i = 0;
  for (Eigen::Index j = 0; j < new_rows.rows(); ++j) {
    if (i < old_rows.rows() && same_row(i, j)) {
      ++i;
      continue;
    }
    added.push_back(j);
    if (static_cast<Eigen::Index>(added.size()) > kMaxAddedRows) return false;
  }
  if (i != old_rows.rows()) return false;  // a row removed or changed
  RowSparse u(static_cast<Eigen::Index>(added.size()), n);
  std::vector<Eigen::Triplet<double>> trip;
  for (size_t k = 0; k < added.size(); ++k)
    for (RowSparse::InnerIterator it(new_rows, added[k]); it; ++it)
      trip.emplace_back(static_cast<int>(k), static_cast<int>(it.col()), it.value());
  u.setFromTriplets(trip.begin(), trip.end());
  const std::shared_ptr<const Factor> kept = f;
  const auto start = Clock::now();
  try {
    correction = std::make_unique<FactorCorrection>(
        [kept](const Eigen::MatrixXd& r) { return kept->solve(r); }, u, mu2);
  } catch (const SolveFailure&) {
    return false;
  }
  factor = f;
  extra_substitutions = correction->setup_substitutions();
  correction_seconds = seconds_since(start);
  return true;
}

Eigen::MatrixXd ConstrainedSolve::Impl::factor_solve(const Eigen::MatrixXd& r) const {
  if (correction && correction_seconds <= factor->seconds) {
    const auto start = Clock::now();
    Eigen::MatrixXd x;
    int substitutions = 0;
    const bool done = correction->solve(
        r, [this](const Eigen::MatrixXd& v) { return apply_penalty(v); }, x, substitutions);
    extra_substitutions += substitutions - 1;
    correction_seconds += seconds_since(start);
    if (done) return x;
  }
  // No correction, or it does not serve (not converging, or costlier than a factorization by
  // now): this system's own factor.
  if (correction && !factor_numeric(mu2, true))
    throw SolveFailure("the penalty system could not be factored");
  return factor->solve(r);
}

bool ConstrainedSolve::Impl::raise_weight(double rate) const {
#ifdef VARSURF_HAVE_SPQR
  if (use_qr) return false;
#endif
  if (!(rate < 1.0)) return false;  // not converging: a heavier weight cannot reach the tolerance
  // Each step multiplies a mode's residual by 1 / (1 + mu^2 s^2) (iterated Tikhonov, s its
  // singular value against the energy): the gain in mu^2 that turns `rate` into kTargetRate.
  const double room = heaviest_mu2 / mu2;
  const double gain = std::min((1.0 / kTargetRate - 1.0) / (1.0 / rate - 1.0), room);
  if (!(gain >= 2.0)) return false;
  if (refactor(mu2 * gain)) return true;
  heaviest_mu2 = mu2;  // no further raises
  return false;
}

bool ConstrainedSolve::Impl::refactor(double weight) const {
  if (factor_numeric(weight, false)) {
    mu2 = weight;
    return true;
  }
  if (!factor_numeric(mu2, false)) throw SolveFailure("the penalty system could not be refactored");
  return false;
}

bool ConstrainedSolve::Impl::factor_numeric(double weight, bool analyze) const {
  if (!factor || correction || factor.use_count() > 1) {
    // A factor shared with an earlier solve stays that solve's: this one gets its own.
    correction.reset();
    factor = std::make_shared<Factor>();
    analyze = true;
  }
  const auto start = Clock::now();
  if (btb.rows() != n) btb = Sparse(samples.transpose()) * samples;
  factor->weight = weight;
  factor->eps = eps;
  factor->rows = sample_rows;
  Sparse m_pen = q_ff + Sparse(weight * btb);
  for (int i = 0; i < n; ++i) m_pen.coeffRef(i, i) += eps;
#ifdef VARSURF_HAVE_CHOLMOD
  Eigen::CholmodDecomposition<Sparse>& cholmod = factor->cholmod;
  // A failed CHOLMOD factorization must not be used by the solve (LDLT takes over below).
  if (analyze) factor->use_cholmod = n > 500;
  if (factor->use_cholmod) {
    {
      const SerialOpenMp one_thread;
      if (analyze) {
        // AMD alone: CHOLMOD's default also tries METIS when AMD's fill is large, which at
        // 256 x 256 poles took 0.82 s of a 1.3 s analysis and factorization, for a factor with
        // 8 % fewer entries.
        cholmod.cholmod().nmethods = 1;
        cholmod.cholmod().method[0].ordering = CHOLMOD_AMD;
        cholmod.compute(m_pen);
      } else {
        cholmod.factorize(m_pen);
      }
    }
    if (cholmod.info() == Eigen::Success) {
      // CHOLMOD checks only the pivots' signs: a factor that cannot reproduce a known solution
      // (rounding beyond the regularization) is refused too.
      const Eigen::VectorXd ones = Eigen::VectorXd::Ones(n);
      const Eigen::VectorXd back = cholmod.solve(Eigen::VectorXd(m_pen * ones));
      if (back.allFinite() && (back - ones).cwiseAbs().maxCoeff() <= 1e-2) {
        factor->seconds = seconds_since(start);
        return true;
      }
    }
    if (!analyze) return false;
    factor->use_cholmod = false;
  }
#endif
  Eigen::SimplicialLDLT<Sparse>& ldlt = factor->ldlt;
  // LDL^T "succeeds" on an indefinite matrix (negative pivots). Each pivot of Q + mu^2 B^T B +
  // eps I is at least its smallest eigenvalue, eps: smaller ones are rounding beyond it (without
  // a regularization, pivots at rounding level mean a singular system).
  if (analyze)
    ldlt.compute(m_pen);
  else
    ldlt.factorize(m_pen);
  if (ldlt.info() != Eigen::Success || !ldlt.vectorD().allFinite()) return false;
  const double smallest = ldlt.vectorD().minCoeff();
  factor->seconds = seconds_since(start);
  return smallest > (eps > 0.0 ? 0.5 * eps : 1e-13 * ldlt.vectorD().cwiseAbs().maxCoeff());
}

ConstrainedSolve::~ConstrainedSolve() = default;

const Eigen::MatrixXd& ConstrainedSolve::reduced_rhs() const {
  return (impl_->mode == SolveMode::penalty || impl_->krylov) ? impl_->sample_rhs : impl_->red.rhs;
}

Eigen::MatrixXd ConstrainedSolve::reduced_rhs(const std::vector<ConstraintSamples>& moved) const {
  // Sampled modes take the rest shape off row by row: a shifted copy of every block was a fifth
  // of a 64 x 64 drag update over a face.
  if (impl_->mode == SolveMode::penalty || impl_->krylov)
    return impl_->samples_rhs(moved, impl_->shift.size() > 0);
  const std::vector<ConstraintSamples> shifted = impl_->shifted(moved);
  const std::vector<ConstraintSamples>& blocks = impl_->shift.size() ? shifted : moved;
  return varsurf::reduced_rhs(impl_->red, blocks, impl_->free_index, impl_->x0);
}

void ConstrainedSolve::Impl::setup_samples(const std::vector<ConstraintSamples>& blocks) {
  // B is written row by row straight into compressed storage and transposed once into column
  // storage, as q_ff is above: through triplets this stage took 2.1 ms of a 14 ms solve of
  // 13 300 samples (benchmark 2), now 1.5 ms.
  size_t rows = 0, entries = 0;
  for (const ConstraintSamples& block : blocks) {
    rows += static_cast<size_t>(block.rows());
    for (const auto& idx : block.index) entries += idx.size();
  }
  const auto rows_b = std::make_shared<RowSparse>(static_cast<Eigen::Index>(rows), n);
  RowSparse& by_row = *rows_b;
  by_row.resizeNonZeros(static_cast<Eigen::Index>(entries));
  int* outer = by_row.outerIndexPtr();
  int* inner = by_row.innerIndexPtr();
  double* values = by_row.valuePtr();
  sample_block.reserve(rows);
  sample_weight.reserve(rows);
  int row = 0, kept = 0;
  outer[0] = 0;
  std::vector<std::pair<int, double>> entry;
  const auto by_column = [](const auto& a, const auto& b) { return a.first < b.first; };
  for (size_t bi = 0; bi < blocks.size(); ++bi) {
    const ConstraintSamples& block = blocks[bi];
    double weight = 0.0;
    for (int k = 0; k < block.rows(); ++k, ++row) {
      const auto& idx = block.index[static_cast<size_t>(k)];
      const Eigen::VectorXd& c = block.coeff[static_cast<size_t>(k)];
      entry.clear();
      for (size_t j = 0; j < idx.size(); ++j) {
        const int f = free_index[static_cast<size_t>(idx[j])];
        if (f >= 0 && c(static_cast<Eigen::Index>(j)) != 0.0)
          entry.emplace_back(f, c(static_cast<Eigen::Index>(j)));
      }
      // Columns ascending, a pole named twice summed (as triplets would be).
      if (!std::is_sorted(entry.begin(), entry.end(), by_column))
        std::sort(entry.begin(), entry.end(), by_column);
      const int start = kept;
      for (const auto& [col, value] : entry) {
        if (kept > start && inner[kept - 1] == col) {
          values[kept - 1] += value;
          continue;
        }
        inner[kept] = col;
        values[kept++] = value;
      }
      outer[row + 1] = kept;
      // A row on fixed poles only still counts in its constraint's residual.
      sample_block.push_back(static_cast<int>(bi));
      sample_weight.push_back(block.weight[static_cast<size_t>(k)]);
      weight += block.weight[static_cast<size_t>(k)];
    }
    block_weight.push_back(weight);
    block_exact.push_back(block.exact);
  }
  by_row.resizeNonZeros(kept);
  samples = by_row;
  sample_rows = rows_b;
  sample_rhs = samples_rhs(blocks);
  if (!start_is_minimum || !(opt.fit_tolerance > 0.0) || row == 0) return;
  // Constraints the start meets as the refinement would judge them met (RMS within
  // fit_tolerance, no sample beyond max_fit_factor times it) are held at the start.
  const Eigen::MatrixXd res = sample_rhs - samples * x0_free;
  std::vector<double> sq, far;
  block_residuals(res, sq, far);
  std::vector<bool> held(block_weight.size(), false);
  for (size_t b = 0; b < block_weight.size(); ++b) {
    held[b] = done(b, sq[b], far[b]);
    held_blocks += held[b] ? 1 : 0;
  }
  if (!held_blocks) return;
  sample_offset = Eigen::MatrixXd::Zero(res.rows(), width);
  for (Eigen::Index i = 0; i < res.rows(); ++i)
    if (held[static_cast<size_t>(sample_block[static_cast<size_t>(i)])])
      sample_offset.row(i) = -res.row(i);
}

Eigen::MatrixXd ConstrainedSolve::Impl::samples_rhs(const std::vector<ConstraintSamples>& blocks,
                                                    bool minus_shift) const {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(sample_block.size()), width);
  Eigen::Index row = 0;
  Eigen::RowVectorXd rhs(width);
  for (const ConstraintSamples& block : blocks)
    for (int k = 0; k < block.rows(); ++k, ++row) {
      if (row >= out.rows()) throw InvalidInput("the moved constraints have more samples");
      if (block.rhs.cols() != width) throw InvalidInput("constraint samples of mixed widths");
      rhs = block.rhs.row(k);  // into storage made once: a row allocated per sample cost more
      const auto& idx = block.index[static_cast<size_t>(k)];
      const Eigen::VectorXd& c = block.coeff[static_cast<size_t>(k)];
      if (minus_shift) take_off_shift(block, k, rhs);
      for (size_t j = 0; j < idx.size(); ++j)
        if (free_index[static_cast<size_t>(idx[j])] < 0)
          rhs -= c(static_cast<Eigen::Index>(j)) * x0.row(idx[j]);
      out.row(row) = rhs;
    }
  if (row != out.rows()) throw InvalidInput("the moved constraints have fewer samples");
  return out;
}

Eigen::MatrixXd ConstrainedSolve::Impl::solve_kkt(const Eigen::MatrixXd& g,
                                                  const Eigen::MatrixXd& b,
                                                  SolveReport& rep) const {
  Eigen::MatrixXd rhs(n + r, width);
  rhs.topRows(n) = g;
  rhs.bottomRows(r) = b;
  Eigen::MatrixXd shifted_rhs = rhs;
  shifted_rhs.topRows(n) += eps * x0_free;
  auto factor = [&](const Eigen::MatrixXd& x) -> Eigen::MatrixXd {
    return kkt_spd ? Eigen::MatrixXd(kkt_ldlt.solve(x)) : Eigen::MatrixXd(lu.solve(x));
  };
  Eigen::MatrixXd sol = factor(shifted_rhs);
  const double rhs_norm = std::max(rhs.norm(), 1e-300);
  int steps = 0;
  for (; steps < opt.refinement_steps; ++steps) {
    const Eigen::MatrixXd res = rhs - kkt * sol;
    if (!(res.norm() > 1e-15 * rhs_norm)) break;
    sol += factor(res);
  }
  rep.inner_iterations = steps;
  rep.kkt_residual = (rhs - kkt * sol).norm() / rhs_norm;
  return sol.topRows(n);
}

void ConstrainedSolve::Impl::block_residuals(const Eigen::MatrixXd& res, std::vector<double>& sq,
                                             std::vector<double>& far) const {
  sq.assign(block_weight.size(), 0.0);
  far.assign(block_weight.size(), 0.0);
  for (Eigen::Index i = 0; i < res.rows(); ++i) {
    const size_t b = static_cast<size_t>(sample_block[static_cast<size_t>(i)]);
    const double r2 = res.row(i).squaredNorm(), w = sample_weight[static_cast<size_t>(i)];
    sq[b] += r2;
    // The row is scaled by sqrt(w): its distance is |res| / sqrt(w).
    if (w > 0.0) far[b] = std::max(far[b], std::sqrt(r2 / w));
  }
}

Eigen::MatrixXd ConstrainedSolve::Impl::solve_penalty(const Eigen::MatrixXd& g,
                                                      const Eigen::MatrixXd& d,
                                                      SolveReport& rep) const {
  rep.back_substitutions = 0;
  // A drag of whole constraints after a solve done in one step: that step again from the
  // precomputed responses, kept if it is done too (the refinement would stop there as well).
  bool draggable =
      opt.drag_responses && mode == SolveMode::penalty && !krylov && samples.rows() > 0;
#ifdef VARSURF_HAVE_SPQR
  draggable = draggable && !use_qr;
#endif
  if (draggable) {
    Eigen::MatrixXd x, bx;
    const auto solve = [this](const Eigen::VectorXd& r) -> Eigen::VectorXd {
      return factor_solve(r);
    };
    int solves = 0;
    if (drag.first_step(d, g, mu2, samples, sample_block, sample_weight, solve, x, bx, solves)) {
      rep.back_substitutions += solves;
      std::vector<double> sq, far;
      block_residuals(d - bx, sq, far);
      bool met = true;
      for (size_t b = 0; b < block_weight.size() && met; ++b) met = done(b, sq[b], far[b]);
      if (met) {
        drag.remember(d, g, mu2, x, bx);
        last_bx = std::move(bx);
        rep.inner_iterations = 1;
        rep.conflict = 0.0;
        rep.back_substitutions += std::exchange(extra_substitutions, 0);
        rep.factor_kept = correction != nullptr;
        return x;  // d_k - d stays what it was
      }
    }
  }
  const double weight_before = mu2;
  Eigen::MatrixXd dk = d;
  if (bregman_offset.rows() == samples.rows() && bregman_offset.cols() == width)
    dk += bregman_offset;
  Refined out = refine(g, d, dk, opt.max_weight_gain > 1.0);
  if (!out.tolerance_met && mu2 != first_mu2) {
    // A raised weight that still misses the tolerance presses harder on what the sheet cannot
    // hold, and roughens it: such a sheet is refined on the configured weight, as W&W's is.
    // It stays there for the later solves (drags) too, which would otherwise each try again.
    // The configured weight's run goes on where it was when the weight was raised (those steps
    // are the ones a solve without raises takes: a raise late in a long run costs no more than
    // the heavier weight's few steps).
    heaviest_mu2 = first_mu2;
    if (refactor(first_mu2)) {
      const int spent = out.steps;
      const std::shared_ptr<const Progress> from = out.before_raise;
      out = refine(g, d, from ? from->dk : d, false, from.get());
      out.steps += spent;
    }
  }
  bregman_offset = out.dk - d;
  last_bx = out.bx;
  if (draggable && out.steps == 1 && mu2 == weight_before && out.bx.rows() == d.rows())
    drag.remember(d, g, mu2, out.x, out.bx);
  else
    drag.forget_step();
  rep.inner_iterations = out.steps;
  rep.back_substitutions += out.steps + std::exchange(extra_substitutions, 0);
  rep.factor_kept = correction != nullptr;
  rep.conflict = out.met || out.worst <= opt.fit_tolerance ? 0.0 : out.worst;
  return out.x;
}

ConstrainedSolve::Impl::Refined ConstrainedSolve::Impl::refine(const Eigen::MatrixXd& g,
                                                               const Eigen::MatrixXd& d,
                                                               Eigen::MatrixXd dk, bool may_raise,
                                                               const Progress* resume) const {
  // W&W's refinement of the penalty solution, on its one factorization: each step solves
  // (Q + mu^2 B^T B) x = f + mu^2 B^T d_k and adds the constraint residual to the data,
  // d_k+1 = d_k + (d - B x) (a Bregman iteration: for consistent constraints it converges to the
  // exactly constrained minimum). It stops when every constraint is within fit_tolerance (RMS,
  // the discrepancy principle; exact constraints: once converged), or when the residual stops
  // falling: what is left is what the space cannot hold, reported as the conflict.
  const Eigen::Index rows = samples.rows();
  Refined out;
  Eigen::MatrixXd& x = out.x;
  x = x0_free;
  Eigen::MatrixXd center = x0_free;
  const double scale =
      std::max({1.0, rows ? d.cwiseAbs().maxCoeff() : 0.0, x0_free.cwiseAbs().maxCoeff()});
  const size_t blocks = block_weight.size();
  std::vector<double> previous(blocks, 1e300), previous_excess(blocks, 1e300);
  std::vector<double> excess_history;  // the largest excess of each step since the last restart
  int it = 0;
  if (resume) {
    x = center = resume->x;
    dk = resume->dk;
    previous = resume->previous;
    previous_excess = resume->previous_excess;
    excess_history = resume->excess_history;
    it = resume->it;
  }
  const int first = it;
  const int max_steps =
      opt.penalty_steps;  // beyond, the space is too coarse: the caller refines it
  for (it = first + 1; it <= max_steps; ++it) {
    check_keep_going(opt);
    const Eigen::MatrixXd next = penalty_step(g + eps * center, dk);
    const double move = (next - x).cwiseAbs().maxCoeff();
    x = next;
    center = x;
    if (rows == 0) {
      if (move <= 1e-13 * scale) break;
      continue;
    }
    out.bx = samples * x;
    const Eigen::MatrixXd res = d - out.bx;
    std::vector<double> sq, far;
    block_residuals(res, sq, far);
    out.met = out.tolerance_met = true;
    bool stalled = true, hopeless = false;
    out.worst = 0.0;
    // The slowest unmet block's rate, and the steps it still needs at that rate.
    double slow_rate = 0.0, slow_needed = 0.0, largest_excess = 0.0;
    for (size_t b = 0; b < blocks; ++b) {
      const double rms = block_weight[b] > 0.0 ? std::sqrt(sq[b] / block_weight[b]) : 0.0;
      out.worst = std::max(out.worst, rms);
      const bool exact = block_exact[b] || opt.fit_tolerance == 0.0;
      if (!done(b, sq[b], far[b])) out.met = false;
      if (!exact && !within(b, sq[b], far[b])) out.tolerance_met = false;
      if (!exact) {
        // How far the block is from its tolerance (1: just met), by RMS and by its farthest
        // sample.
        const double excess = std::max(
            rms / opt.fit_tolerance,
            opt.max_fit_factor > 0.0 ? far[b] / (opt.max_fit_factor * opt.fit_tolerance) : 0.0);
        if (excess > 1.0 && previous_excess[b] < 1e299) {
          const double rate = excess / previous_excess[b];
          const double needed = rate < 1.0 ? std::log(excess) / -std::log(rate)
                                           : std::numeric_limits<double>::infinity();
          if (needed > slow_needed) {
            slow_needed = needed;
            slow_rate = rate;
          }
        }
        previous_excess[b] = excess;
        largest_excess = std::max(largest_excess, excess);
      }
      // Less than 0.1 % progress a step: what is left converges too slowly to wait for (the
      // space cannot hold it, or only in directions the refinement barely reaches).
      if (rms < previous[b] * (1.0 - 1e-3) && rms > 1e-13 * scale) stalled = false;
      if (opt.give_up_early && !exact && rms > opt.fit_tolerance && it >= kWarmUpSteps &&
          previous[b] < 1e299) {
        // At the last step's rate (the iteration converges linearly), the steps still needed.
        const double rate = rms / previous[b];
        const double needed = rate < 1.0 ? std::log(opt.fit_tolerance / rms) / std::log(rate)
                                         : std::numeric_limits<double>::infinity();
        if (needed > 2.0 * (max_steps - it)) hopeless = true;
      }
      previous[b] = rms;
    }
    if (out.met || hopeless || (stalled && move <= 1e-12 * scale)) break;
    dk += res;
    excess_history.push_back(largest_excess);
    if (!may_raise || !(slow_needed > kStepBudget)) continue;
    const double stepped_on = mu2;
    if (!raise_weight(slow_rate)) {
      // Still slow on the heaviest weight allowed, over the last kRateSpan steps (one step's
      // rate jumps about): most likely constraints that contradict each other, the refinement
      // creeping toward a residual beyond the tolerance at any weight.
      const size_t k = excess_history.size();
      if (mu2 != first_mu2 && k > kRateSpan) {
        const double e = excess_history[k - 1];
        const double rate = std::pow(e / excess_history[k - 1 - kRateSpan], 1.0 / kRateSpan);
        if (!(rate < 1.0) || std::log(e) / -std::log(rate) > 4.0 * kStepBudget) break;
      }
    } else {
      // Restarted on the heavier weight: its refinement, not a continuation of this one. Where
      // the configured weight's stood is kept: should the heavier one fail, that run goes on.
      if (!out.before_raise && stepped_on == first_mu2)
        out.before_raise = std::make_shared<const Progress>(
            Progress{x, dk, previous, previous_excess, excess_history, it});
      dk = d;
      x = center = x0_free;
      std::fill(previous.begin(), previous.end(), 1e300);
      std::fill(previous_excess.begin(), previous_excess.end(), 1e300);
      excess_history.clear();
    }
  }
  out.steps = std::min(it, max_steps) - first;
  out.dk = std::move(dk);
  return out;
}

Eigen::MatrixXd ConstrainedSolve::Impl::solve_krylov(const Eigen::MatrixXd& g,
                                                     const Eigen::MatrixXd& d,
                                                     SolveReport& rep) const {
  // CGLS on min |B (x - x0) - r0| from x0: its iterations filter the constraints' singular
  // directions like a truncated SVD (Hansen's regularizing iterations), and the L-curve over the
  // iteration count chooses where to stop. A first run draws the L-curve, a second stops at its
  // corner: the TSVD answer. MTSVD keeps what that fit asks of the constraints (B x_k, data now
  // consistent) and lets the energy place the rest, through the penalty mode's factorization
  // (Michalik & Bruderlin: take k from TSVD, then solve the side constraint once).
  const int max_it = std::min(std::max(n, 1), 400);
  const Eigen::MatrixXd r0 = d - samples * x0_free;
  auto run = [&](int stop_at, std::vector<double>* rho, std::vector<double>* eta) {
    Eigen::MatrixXd y = Eigen::MatrixXd::Zero(n, width), r = r0;
    Eigen::MatrixXd s = samples.transpose() * r, p = s;
    Eigen::VectorXd gamma = s.colwise().squaredNorm().transpose();
    const double floor = 1e-28 * std::max(gamma.maxCoeff(), 1e-300);
    for (int k = 1; k <= stop_at; ++k) {
      for (Eigen::Index c = 0; c < width; ++c) {
        if (!(gamma(c) > floor)) continue;
        const Eigen::VectorXd q = samples * p.col(c);
        const double qq = q.squaredNorm();
        if (!(qq > 0.0)) continue;
        const double alpha = gamma(c) / qq;
        y.col(c) += alpha * p.col(c);
        r.col(c) -= alpha * q;
        s.col(c) = samples.transpose() * r.col(c);
        const double next = s.col(c).squaredNorm();
        p.col(c) = s.col(c) + (next / gamma(c)) * p.col(c);
        gamma(c) = next;
      }
      if (rho) {
        rho->push_back(r.norm());
        eta->push_back(y.norm());
      }
      if (!(gamma.maxCoeff() > floor)) break;
    }
    return Eigen::MatrixXd(x0_free + y);
  };
  LCurve curve;
  run(max_it, &curve.residual, &curve.solution_norm);
  for (size_t k = 0; k < curve.residual.size(); ++k) curve.k.push_back(static_cast<int>(k + 1));
  curve.corner = lcurve_corner(curve.residual, curve.solution_norm);
  rep.lcurve = curve;
  const Eigen::MatrixXd xk = run(curve.corner, nullptr, nullptr);
  if (mode == SolveMode::tsvd) {
    rep.inner_iterations = curve.corner;
    return xk;
  }
  return solve_penalty(g, samples * xk, rep);
}

Eigen::MatrixXd ConstrainedSolve::Impl::solve_cg(const Eigen::MatrixXd& g, const Eigen::MatrixXd& b,
                                                 SolveReport& rep) const {
  // Elimination: x = x_s + P y with x_s the start projected onto {A x = b} and P the projector
  // onto null(A); conjugate gradients on the energy over that affine set, preconditioned by
  // P D^-1 P (Jacobi), which keeps every iterate feasible.
  Eigen::MatrixXd out(n, width);
  const int max_it = std::max(1000, 20 * n);
  int worst = 0;
  for (Eigen::Index c = 0; c < width; ++c) {
    Eigen::VectorXd x = x0_free.col(c);
    if (r > 0) x += a.transpose() * (b.col(c) - a * x);
    auto apply = [&](const Eigen::VectorXd& v) { return Eigen::VectorXd(q_ff * v + eps * v); };
    const Eigen::VectorXd rhs = g.col(c) + eps * x0_free.col(c);
    const Eigen::VectorXd qx = apply(x);
    Eigen::VectorXd res = project(rhs - qx);
    Eigen::VectorXd z = project(inv_diag.cwiseProduct(res));
    Eigen::VectorXd p = z;
    double rz = res.dot(z);
    // A projected residual at the rounding level of the terms it is made of is converged: when
    // the constraints leave (almost) no freedom it is all rounding, and stepping along it
    // (alpha = rounding / rounding) threw a fully pinned sheet 0.3 off.
    const double rounding =
        64.0 * std::numeric_limits<double>::epsilon() * (rhs.norm() + qx.norm());
    const double stop = std::max(opt.cg_tolerance * res.norm(), std::max(rounding, 1e-300));
    int it = 0;
    while (it < max_it && res.norm() > stop) {
      if (it % 16 == 0) check_keep_going(opt);
      const Eigen::VectorXd qp = project(apply(p));
      const double pqp = p.dot(qp);
      if (!(pqp > 0.0)) break;  // nothing left to lower along p
      const double alpha = rz / pqp;
      x += alpha * p;
      res -= alpha * qp;
      z = project(inv_diag.cwiseProduct(res));
      const double rz_next = res.dot(z);
      p = z + (rz_next / rz) * p;
      rz = rz_next;
      ++it;
    }
    worst = std::max(worst, it);
    out.col(c) = x;
  }
  rep.inner_iterations = worst;
  return out;
}

Eigen::MatrixXd ConstrainedSolve::solve(const Eigen::MatrixXd& f, const Eigen::MatrixXd& b,
                                        SolveReport& rep) const {
  const Impl& m = *impl_;
  Eigen::MatrixXd x = m.x0;
  if (m.n == 0) return m.shift.size() ? Eigen::MatrixXd(x + m.shift) : x;
  const auto t = Clock::now();
  const Eigen::Index expected = (m.mode == SolveMode::penalty || m.krylov) ? m.samples.rows() : m.r;
  if (b.rows() != expected || b.cols() != m.width)
    throw InvalidInput("reduced right-hand side size");
  Eigen::MatrixXd sol;
  const bool sampled = m.mode == SolveMode::penalty || m.krylov;
  const Eigen::MatrixXd held_b =
      sampled && m.sample_offset.size() ? Eigen::MatrixXd(b + m.sample_offset) : Eigen::MatrixXd();
  const Eigen::MatrixXd& d = held_b.size() ? held_b : b;
  if (m.krylov) {
    sol = m.solve_krylov(m.energy_rhs(f), d, rep);
  } else
    switch (m.mode) {
      case SolveMode::exact:
      case SolveMode::mtsvd:
        sol = m.solve_kkt(m.energy_rhs(f), b, rep);
        break;
      case SolveMode::penalty:
        sol = m.solve_penalty(m.energy_rhs(f), d, rep);
        break;
      case SolveMode::cg:
        sol = m.solve_cg(m.energy_rhs(f), b, rep);
        break;
      case SolveMode::tsvd:
      case SolveMode::automatic:
      case SolveMode::multigrid:  // refused by the constructor
        // Michalik & Bruderlin eq. 3-4: F = F_k + V_{k+1} V_{k+1}^T F_0, i.e. the start moved
        // by the least change that meets the kept rows.
        sol = m.x0_free;
        if (m.r > 0) sol += m.a.transpose() * (b - m.a * m.x0_free);
        break;
    }
  if (!sol.allFinite()) throw SolveFailure("the solve produced non-finite poles");
  if (m.mode == SolveMode::penalty && !m.krylov && m.last_bx.rows() == b.rows() &&
      m.samples.rows() > 0) {
    rep.constraint_residual = (m.last_bx - b).cwiseAbs().maxCoeff();  // B sol, kept by the solve
  } else if (m.mode == SolveMode::penalty || m.krylov) {
    if (m.samples.rows() > 0) rep.constraint_residual = (m.samples * sol - b).cwiseAbs().maxCoeff();
  } else if (m.r > 0) {
    rep.constraint_residual = (m.a * sol - b).cwiseAbs().maxCoeff();
  }
  for (int i = 0; i < m.n; ++i) x.row(m.free_cols[static_cast<size_t>(i)]) = sol.row(i);
  if (m.shift.size()) x += m.shift;
  rep.solve_seconds = seconds_since(t);
  return x;
}

}  // namespace varsurf
