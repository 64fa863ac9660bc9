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
using Sparse = Eigen::SparseMatrix<double>;

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
  if (pb.rest_poles.rows() != 0 &&
      (pb.rest_poles.rows() != pb.space.size() || !pb.rest_poles.allFinite()))
    throw InvalidInput("rest shape: expected " + std::to_string(pb.space.size()) + " finite poles");
  for (int k : pb.fixed_poles)
    if (k < 0 || k >= pb.space.size()) throw InvalidInput("fixed pole index out of range");
  if (!(opt.regularization >= 0.0) || !std::isfinite(opt.regularization))
    throw InvalidInput("regularization must be a finite non-negative number");
  if (opt.refinement_steps < 0 || opt.refinement_steps > 20)
    throw InvalidInput("refinement steps must be in 0..20");
}

// Samples of a list of constraints, naming the failing one.
template <class C, class F>
void sample_all(const std::vector<C>& list, const char* what, F&& sample,
                std::vector<ConstraintSamples>& out) {
  for (size_t i = 0; i < list.size(); ++i) {
    try {
      out.push_back(sample(list[i]));
    } catch (const InvalidInput& e) {
      throw InvalidInput(std::string(what) + " " + std::to_string(i) + ": " + e.what());
    }
  }
}

// Q (x) I_3 in the coupled ordering: column 3 k + c is coordinate c of pole k.
Sparse kron_identity3(const Sparse& q) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<size_t>(3 * q.nonZeros()));
  for (int col = 0; col < q.outerSize(); ++col)
    for (Sparse::InnerIterator it(q, col); it; ++it)
      for (int c = 0; c < 3; ++c) t.emplace_back(3 * it.row() + c, 3 * col + c, it.value());
  Sparse out(3 * q.rows(), 3 * q.cols());
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

Eigen::MatrixXd flatten(const Eigen::MatrixX3d& m) {  // rows 3 k + c
  Eigen::MatrixXd out(3 * m.rows(), 1);
  for (Eigen::Index k = 0; k < m.rows(); ++k)
    for (int c = 0; c < 3; ++c) out(3 * k + c, 0) = m(k, c);
  return out;
}

// One equality-constrained quadratic problem: minimize x^T Q x - 2 f^T x over the free columns
// subject to the constraint samples (reduced to independent rows), with fixed columns at x0.
// Each column of f / x0 is one right-hand side sharing Q and the constraint matrix.
struct Quadratic {
  Sparse q;
  Eigen::MatrixXd f;
  Eigen::MatrixXd x0;       // start values, and the values of fixed columns
  std::vector<bool> fixed;  // per column
  std::vector<ConstraintSamples> blocks;
};

Eigen::MatrixXd solve_quadratic(const Quadratic& pb, const SolveOptions& opt, SolveReport& rep) {
  const int total = static_cast<int>(pb.q.rows());
  std::vector<int> free_index(static_cast<size_t>(total), -1);
  std::vector<int> free_cols;
  for (int k = 0; k < total; ++k)
    if (!pb.fixed[static_cast<size_t>(k)]) {
      free_index[static_cast<size_t>(k)] = static_cast<int>(free_cols.size());
      free_cols.push_back(k);
    }
  const int n = static_cast<int>(free_cols.size());
  rep.unknowns = n;
  Eigen::MatrixXd x = pb.x0;
  if (n == 0) return x;
  const Eigen::Index width = pb.x0.cols();

  auto t = Clock::now();
  const ReducedConstraints red = reduce_constraints(
      pb.blocks, free_index, pb.x0, n, opt.rank_tolerance, opt.fit_tolerance, opt.keep_tolerance);
  const int r = static_cast<int>(red.rows.rows());
  rep.constraint_samples = red.samples;
  rep.constraint_rank = r;
  rep.clusters = red.clusters;
  rep.conflict = red.conflict;
  rep.reduce_seconds = seconds_since(t);

  // KKT system [Q_ff, A^T; A, 0] [x_f; y] = [f_f - Q_fc x_c; b] (Welch & Witkin eq. 9).
  t = Clock::now();
  double diag_mean = 0.0;
  for (int k : free_cols) diag_mean += pb.q.coeff(k, k);
  diag_mean /= n;
  const double eps = opt.regularization * (diag_mean > 0.0 ? diag_mean : 1.0);

  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(pb.q.nonZeros() + 2 * red.rows.nonZeros()));
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n + r, width);
  for (int k = 0; k < n; ++k) rhs.row(k) = pb.f.row(free_cols[static_cast<size_t>(k)]);
  for (int col = 0; col < pb.q.outerSize(); ++col) {
    const int fc = free_index[static_cast<size_t>(col)];
    for (Sparse::InnerIterator it(pb.q, col); it; ++it) {
      const int fr = free_index[static_cast<size_t>(it.row())];
      if (fr < 0) continue;
      if (fc >= 0)
        trip.emplace_back(fr, fc, it.value());
      else
        rhs.row(fr) -= it.value() * pb.x0.row(col);
    }
  }
  for (int row = 0; row < r; ++row) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(red.rows, row); it; ++it) {
      trip.emplace_back(n + row, static_cast<int>(it.col()), it.value());
      trip.emplace_back(static_cast<int>(it.col()), n + row, it.value());
    }
  }
  rhs.bottomRows(r) = red.rhs;
  Sparse kkt(n + r, n + r);
  kkt.setFromTriplets(trip.begin(), trip.end());
  kkt.makeCompressed();
  // The factored matrix carries eps on the unknowns' diagonal so that directions neither energy
  // nor constraints determine stay where they started; refinement against the exact matrix then
  // removes the eps bias from every determined direction (a proximal-point iteration).
  Sparse shifted = kkt;
  for (int i = 0; i < n; ++i) shifted.coeffRef(i, i) += eps;

  Eigen::SparseLU<Sparse, Eigen::COLAMDOrdering<int>> lu;
  lu.analyzePattern(shifted);
  lu.factorize(shifted);
  if (lu.info() != Eigen::Success)
    throw SolveFailure("the constrained system is singular: " + lu.lastErrorMessage());
  rep.factor_seconds = seconds_since(t);

  // One factorization serves every right-hand side (x, y and z when separable).
  t = Clock::now();
  Eigen::MatrixXd shifted_rhs = rhs;
  for (int i = 0; i < n; ++i)
    shifted_rhs.row(i) += eps * pb.x0.row(free_cols[static_cast<size_t>(i)]);
  Eigen::MatrixXd sol = lu.solve(shifted_rhs);
  const double rhs_norm = std::max(rhs.norm(), 1e-300);
  for (int step = 0; step < opt.refinement_steps; ++step) {
    const Eigen::MatrixXd res = rhs - kkt * sol;
    if (!(res.norm() > 1e-15 * rhs_norm)) break;
    sol += lu.solve(res);
  }
  if (!sol.allFinite()) throw SolveFailure("the solve produced non-finite poles");
  rep.kkt_residual = (rhs - kkt * sol).norm() / rhs_norm;
  if (r > 0) rep.constraint_residual = (red.rows * sol.topRows(n) - red.rhs).cwiseAbs().maxCoeff();
  for (int i = 0; i < n; ++i) x.row(free_cols[static_cast<size_t>(i)]) = sol.row(i);
  rep.solve_seconds = seconds_since(t);
  return x;
}

Eigen::MatrixX3d unflatten(const Eigen::MatrixXd& x) {
  Eigen::MatrixX3d poles(x.rows() / 3, 3);
  for (Eigen::Index k = 0; k < poles.rows(); ++k)
    for (int c = 0; c < 3; ++c) poles(k, c) = x(3 * k + c, 0);
  return poles;
}

// Repellers, shape attractors and pressure: re-linearize at the current poles, solve, move at most
// step_limit. Every iterate is a convex combination of feasible solutions, so the constraints keep
// holding.
Eigen::MatrixXd iterate_nonlinear(const SheetProblem& pb, const SolveOptions& opt,
                                  const OperatorScales& scales, const Quadratic& base,
                                  Eigen::MatrixXd x, SolveReport& rep) {
  if (opt.max_iterations < 1 || !(opt.step_limit > 0.0) || !(opt.nonlinear_tolerance > 0.0))
    throw InvalidInput("nonlinear solve: max_iterations, step_limit and tolerance must be > 0");
  const Eigen::Vector3d extent =
      pb.initial_poles.colwise().maxCoeff() - pb.initial_poles.colwise().minCoeff();
  const double size = std::max(extent.norm(), 1e-300);
  const double limit = opt.step_limit * size, tol = opt.nonlinear_tolerance * size;
  const int poles = pb.space.size();
  rep.converged = false;
  for (int it = 1; it <= opt.max_iterations; ++it) {
    const Eigen::MatrixX3d current = unflatten(x);
    QuadraticTerms model(poles);
    for (size_t i = 0; i < pb.repellers.size(); ++i) {
      try {
        add_repeller_model(pb.space, pb.repellers[i], scales.value, current, 1e-6 * size, model);
      } catch (const InvalidInput& e) {
        throw InvalidInput("repeller " + std::to_string(i) + ": " + e.what());
      }
    }
    for (size_t i = 0; i < pb.shape_attractors.size(); ++i) {
      try {
        add_shape_attractor_model(pb.space, pb.shape_attractors[i], scales.value, current, model);
      } catch (const InvalidInput& e) {
        throw InvalidInput("shape attractor " + std::to_string(i) + ": " + e.what());
      }
    }
    add_pressure_force(pb.space, pb.pressure, current, model);
    Quadratic step = base;
    if (model.uses_coupled()) {
      Sparse extra(3 * poles, 3 * poles);
      extra.setFromTriplets(model.coupled.begin(), model.coupled.end());
      step.q += extra;
    }
    step.f += model.coupled_f;
    SolveReport inner;
    Eigen::MatrixXd next = solve_quadratic(step, opt, inner);
    const double move = (next - x).cwiseAbs().maxCoeff();
    if (move > limit) next = x + (limit / move) * (next - x);
    x = next;
    rep.iterations = it;
    rep.last_step = std::min(move, limit);
    rep.constraint_rank = inner.constraint_rank;
    rep.constraint_residual = inner.constraint_residual;
    rep.kkt_residual = inner.kkt_residual;
    if (move <= tol) {
      rep.converged = true;
      break;
    }
  }
  return x;
}

}  // namespace

SolveResult solve_sheet(const SheetProblem& pb, const SolveOptions& opt) {
  const auto start = Clock::now();
  validate_problem(pb, opt);
  SolveResult result;
  SolveReport& rep = result.report;
  const SplineSpace& sp = pb.space;
  const int poles = sp.size();

  auto t = Clock::now();
  Sparse h = assemble_thin_plate(sp, pb.energy);
  QuadraticTerms terms(poles);
  if (pb.rest_poles.rows() != 0) terms.separable_f += h * pb.rest_poles;
  OperatorScales scales;
  if (!pb.attractors.empty() || !pb.directors.empty() || !pb.repellers.empty() ||
      !pb.shape_attractors.empty())
    scales = operator_scales(sp, h);
  for (size_t i = 0; i < pb.attractors.size(); ++i) {
    try {
      add_attractor(sp, pb.attractors[i], scales.value, terms);
    } catch (const InvalidInput& e) {
      throw InvalidInput("attractor " + std::to_string(i) + ": " + e.what());
    }
  }
  for (size_t i = 0; i < pb.directors.size(); ++i) {
    try {
      add_director(sp, pb.directors[i], scales.gradient, terms);
    } catch (const InvalidInput& e) {
      throw InvalidInput("director " + std::to_string(i) + ": " + e.what());
    }
  }
  if (!terms.separable.empty()) {
    Sparse extra(poles, poles);
    extra.setFromTriplets(terms.separable.begin(), terms.separable.end());
    h += extra;
  }

  std::vector<ConstraintSamples> separable, coupled;
  sample_all(
      pb.points, "point constraint", [&](const auto& c) { return sample_point(sp, c); }, separable);
  sample_all(
      pb.curves, "curve", [&](const auto& c) { return sample_curve(sp, c); }, separable);
  sample_all(
      pb.tangents, "tangent constraint", [&](const auto& c) { return sample_tangent(sp, c); },
      separable);
  sample_all(
      pb.normals, "normal constraint", [&](const auto& c) { return sample_normal(sp, c); },
      coupled);
  sample_all(
      pb.plane_points, "point-in-plane constraint",
      [&](const auto& c) { return sample_plane_point(sp, c); }, coupled);
  sample_all(
      pb.line_points, "point-on-line constraint",
      [&](const auto& c) { return sample_line_point(sp, c); }, coupled);
  sample_all(
      pb.ribbons, "ribbon", [&](const auto& c) { return sample_ribbon(sp, c); }, coupled);

  const bool nonlinear =
      !pb.repellers.empty() || !pb.shape_attractors.empty() || pb.pressure != 0.0;
  if (!std::isfinite(pb.pressure)) throw InvalidInput("pressure must be finite");
  Quadratic quad;
  rep.coupled = opt.force_coupled || nonlinear || !coupled.empty() || terms.uses_coupled();
  if (!rep.coupled) {
    quad.q = std::move(h);
    quad.f = terms.separable_f;
    quad.x0 = pb.initial_poles;
    quad.fixed.assign(static_cast<size_t>(poles), false);
    for (int k : pb.fixed_poles) quad.fixed[static_cast<size_t>(k)] = true;
    quad.blocks = std::move(separable);
  } else {
    quad.q = kron_identity3(h);
    if (terms.uses_coupled()) {
      Sparse extra(3 * poles, 3 * poles);
      extra.setFromTriplets(terms.coupled.begin(), terms.coupled.end());
      quad.q += extra;
    }
    quad.f = flatten(terms.separable_f) + terms.coupled_f;
    quad.x0 = flatten(pb.initial_poles);
    quad.fixed.assign(static_cast<size_t>(3 * poles), false);
    for (int k : pb.fixed_poles)
      for (int c = 0; c < 3; ++c) quad.fixed[static_cast<size_t>(3 * k + c)] = true;
    for (const ConstraintSamples& s : separable) quad.blocks.push_back(to_coupled(s));
    for (ConstraintSamples& s : coupled) quad.blocks.push_back(std::move(s));
  }
  rep.assemble_seconds = seconds_since(t);

  Eigen::MatrixXd x = solve_quadratic(quad, opt, rep);
  if (nonlinear) x = iterate_nonlinear(pb, opt, scales, quad, x, rep);
  if (!rep.coupled) {
    result.poles = x;
  } else {
    result.poles = unflatten(x);
  }
  rep.total_seconds = seconds_since(start);
  return result;
}

}  // namespace varsurf
