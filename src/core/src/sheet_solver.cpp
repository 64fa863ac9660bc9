// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/sheet_solver.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <string>

#include "constrained_solve.hpp"
#include "free_block.hpp"
#include "sheet_assembly.hpp"
#include "solve_limits.hpp"
#include "stopwatch.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/multigrid.hpp"
#include "varsurf/core/pde_energy.hpp"

namespace varsurf {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

void validate_problem(const SheetProblem& pb, const SolveOptions& opt) {
  pb.space.validate();
  if (pb.space.size() > opt.max_unknowns)
    throw ResourceLimit("the sheet has " + std::to_string(pb.space.size()) +
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
  if (pb.kept_region) check_region(pb.space, *pb.kept_region, "kept region");
}

// G2 along curves or curvatures at points: conditions iterated on the whole solve.
bool has_curvature_conditions(const SheetProblem& pb) {
  return !pb.curvatures.empty() || !pb.point_curvatures.empty();
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

}  // namespace

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

namespace {

Eigen::MatrixXd solve_quadratic(const Quadratic& pb, const SolveOptions& opt, SolveReport& rep) {
  const ConstrainedSolve solver(pb, opt, rep);
  return solver.solve(pb.f, solver.reduced_rhs(), rep);
}

}  // namespace

Eigen::MatrixX3d unflatten(const Eigen::MatrixXd& x) {
  Eigen::MatrixX3d poles(x.rows() / 3, 3);
  for (Eigen::Index k = 0; k < poles.rows(); ++k)
    for (int c = 0; c < 3; ++c) poles(k, c) = x(3 * k + c, 0);
  return poles;
}

namespace {

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
  // A pressure alone changes only the right-hand side: one factorization serves every step
  // (measured on a 19 x 19 pillow sheet: 3.8 s re-factoring each step, far less this way).
  std::unique_ptr<ConstrainedSolve> fixed_system;
  if (pb.repellers.empty() && pb.shape_attractors.empty()) {
    SolveReport setup;
    fixed_system = std::make_unique<ConstrainedSolve>(base, opt, setup);
  }
  for (int it = 1; it <= opt.max_iterations; ++it) {
    check_keep_going(opt);
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
    add_pressure_force(pb.space, pb.pressure, current, model, pb.kept_region);
    Quadratic step =
        fixed_system ? Quadratic{Sparse(), base.f, Eigen::MatrixXd(), {}, {}, {}} : base;
    if (model.uses_coupled()) {
      Sparse extra(3 * poles, 3 * poles);
      extra.setFromTriplets(model.coupled.begin(), model.coupled.end());
      step.q += extra;
      if (step.rest.size()) step.f -= extra * step.rest;  // the solve centres Q on the rest
    }
    step.f += model.coupled_f;
    SolveReport inner;
    Eigen::MatrixXd next = fixed_system
                               ? fixed_system->solve(step.f, fixed_system->reduced_rhs(), inner)
                               : solve_quadratic(step, opt, inner);
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

namespace {

// The sheet's quadratic problem, assembled once.
struct Assembled {
  Quadratic quad;
  OperatorScales scales;
  bool nonlinear = false;
};

// Constraint samples of the problem, in the solve's ordering (separable ones made coupled when
// the solve is coupled).
using CurveSampler = std::function<ConstraintSamples(size_t, const CurveConstraint&)>;

std::vector<ConstraintSamples> sample_constraints(const SheetProblem& pb, bool coupled_solve,
                                                  const CurveSampler& curve_sampler = nullptr) {
  const SplineSpace& sp = pb.space;
  std::vector<ConstraintSamples> separable, coupled;
  sample_all(
      pb.points, "point constraint", [&](const auto& c) { return sample_point(sp, c); }, separable);
  for (size_t i = 0; i < pb.curves.size(); ++i) {
    try {
      separable.push_back(curve_sampler ? curve_sampler(i, pb.curves[i])
                                        : sample_curve(sp, pb.curves[i]));
    } catch (const InvalidInput& e) {
      throw InvalidInput("curve " + std::to_string(i) + ": " + e.what());
    }
  }
  sample_all(
      pb.tangents, "tangent constraint", [&](const auto& c) { return sample_tangent(sp, c); },
      separable);
  if (pb.closed_u || pb.closed_v) {
    std::vector<bool> fixed(static_cast<size_t>(sp.size()), false);
    for (int k : pb.fixed_poles) fixed[static_cast<size_t>(k)] = true;
    for (int direction : {0, 1}) {
      if (!(direction == 0 ? pb.closed_u : pb.closed_v)) continue;
      ConstraintSamples seam = sample_seam(sp, direction, fixed);
      // The rows ask the displacement from the start to be continuous: the start's own mismatch
      // (a parametrization only C1 across the seam) is their right-hand side.
      for (Eigen::Index r = 0; r < seam.rows(); ++r)
        for (size_t c = 0; c < seam.index[static_cast<size_t>(r)].size(); ++c)
          seam.rhs.row(r) += seam.coeff[static_cast<size_t>(r)](static_cast<Eigen::Index>(c)) *
                             pb.initial_poles.row(seam.index[static_cast<size_t>(r)][c]);
      if (seam.rows() > 0) separable.push_back(std::move(seam));
    }
  }
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
  if (!coupled_solve) return separable;
  std::vector<ConstraintSamples> out;
  for (const ConstraintSamples& s : separable) out.push_back(to_coupled(s));
  for (ConstraintSamples& s : coupled) out.push_back(std::move(s));
  return out;
}

bool has_coupled_constraints(const SheetProblem& pb) {
  return !pb.normals.empty() || !pb.plane_points.empty() || !pb.line_points.empty() ||
         !pb.ribbons.empty() || has_curvature_conditions(pb);
}

// Before anything large is allocated: the solve's size, 3 unknowns a pole if it couples x, y, z.
void check_sheet_memory(const SheetProblem& pb, const SolveOptions& opt) {
  const bool coupled =
      opt.force_coupled || has_coupled_constraints(pb) || !pb.directors.empty() ||
      !pb.repellers.empty() || !pb.shape_attractors.empty() || pb.pressure != 0.0 ||
      std::any_of(pb.attractors.begin(), pb.attractors.end(),
                  [](const Attractor& a) { return a.kind != AttractorKind::point; });
  const long long width = coupled ? 3 : 1;
  const long long row = (2LL * pb.space.degree_u + 1) * (2LL * pb.space.degree_v + 1);
  check_memory(width * pb.space.size(), row, SolveMode::penalty, opt, "the sheet");
}

Assembled assemble(const SheetProblem& pb, const SolveOptions& opt, SolveReport& rep,
                   const CurveSampler& curve_sampler = nullptr) {
  check_sheet_memory(pb, opt);
  const SplineSpace& sp = pb.space;
  const int poles = sp.size();
  Assembled out;
  Sparse h;
  if (pb.pde)
    h = pb.kept_region ? assemble_pde(sp, *pb.pde, *pb.kept_region, pb.overhang_energy)
                       : assemble_pde(sp, *pb.pde);
  else
    h = pb.kept_region ? assemble_thin_plate(sp, pb.energy, *pb.kept_region, pb.overhang_energy)
                       : assemble_thin_plate(sp, pb.energy);
  QuadraticTerms terms(poles);
  const bool rest = pb.rest_poles.rows() != 0;  // the energy acts on the displacement from it
  if (!pb.attractors.empty() || !pb.directors.empty() || !pb.repellers.empty() ||
      !pb.shape_attractors.empty())
    out.scales = operator_scales(sp, h);
  for (size_t i = 0; i < pb.attractors.size(); ++i) {
    try {
      add_attractor(sp, pb.attractors[i], out.scales.value, terms);
    } catch (const InvalidInput& e) {
      throw InvalidInput("attractor " + std::to_string(i) + ": " + e.what());
    }
  }
  for (size_t i = 0; i < pb.directors.size(); ++i) {
    try {
      add_director(sp, pb.directors[i], out.scales.gradient, terms);
    } catch (const InvalidInput& e) {
      throw InvalidInput("director " + std::to_string(i) + ": " + e.what());
    }
  }
  if (!terms.separable.empty()) {
    Sparse extra(poles, poles);
    extra.setFromTriplets(terms.separable.begin(), terms.separable.end());
    h += extra;
    // The solve centres all of Q on the rest shape; the operators' terms are not centred.
    if (rest) terms.separable_f -= extra * pb.rest_poles;
  }
  if (!std::isfinite(pb.pressure)) throw InvalidInput("pressure must be finite");
  out.nonlinear = !pb.repellers.empty() || !pb.shape_attractors.empty() || pb.pressure != 0.0;
  rep.coupled =
      opt.force_coupled || out.nonlinear || has_coupled_constraints(pb) || terms.uses_coupled();
  Quadratic& quad = out.quad;
  quad.blocks = sample_constraints(pb, rep.coupled, curve_sampler);
  if (!rep.coupled) {
    quad.q = std::move(h);
    quad.f = terms.separable_f;
    quad.x0 = pb.initial_poles;
    quad.fixed.assign(static_cast<size_t>(poles), false);
    for (int k : pb.fixed_poles) quad.fixed[static_cast<size_t>(k)] = true;
    if (rest) quad.rest = pb.rest_poles;
  } else {
    quad.q = kron_identity3(h);
    quad.f = flatten(terms.separable_f) + terms.coupled_f;
    if (rest) quad.rest = flatten(pb.rest_poles);
    if (terms.uses_coupled()) {
      Sparse extra(3 * poles, 3 * poles);
      extra.setFromTriplets(terms.coupled.begin(), terms.coupled.end());
      quad.q += extra;
      if (rest) quad.f -= extra * quad.rest;
    }
    quad.x0 = flatten(pb.initial_poles);
    quad.fixed.assign(static_cast<size_t>(3 * poles), false);
    for (int k : pb.fixed_poles)
      for (int c = 0; c < 3; ++c) quad.fixed[static_cast<size_t>(3 * k + c)] = true;
  }
  return out;
}

Eigen::MatrixX3d to_poles(const Eigen::MatrixXd& x, bool coupled) {
  return coupled ? unflatten(x) : Eigen::MatrixX3d(x);
}

// G2: Newton steps, each the whole constrained solve with the curvature rows linearized at the
// last poles (the first solve, without them, is the G1 answer they start from). The energy's
// Hessian lacks the conditions' curvature (their multipliers are not kept), so convergence is
// linear (measured: the jump falls about 4x a step); it stops when every sample's relative jump
// is below curvature_tolerance, the poles stop moving or the jump stops falling, and keeps the
// best step.
Eigen::MatrixXd iterate_curvature(const SheetProblem& pb, const SolveOptions& opt,
                                  const Assembled& as, Eigen::MatrixXd x, SolveReport& rep) {
  if (!(opt.curvature_tolerance > 0.0) || opt.max_curvature_iterations < 1)
    throw InvalidInput("G2: curvature_tolerance and max_curvature_iterations must be > 0");
  const Eigen::Vector3d extent =
      pb.initial_poles.colwise().maxCoeff() - pb.initial_poles.colwise().minCoeff();
  const double size = std::max(extent.norm(), 1e-300);
  const double tol = opt.nonlinear_tolerance * size, limit = opt.step_limit * size;
  // Progress is judged by the RMS jump: where two G2 edges meet at a corner their neighbours can
  // ask for different curvatures (three fillets at a box's corner), and the largest jump, there,
  // need not fall while the rest of the edges comes right.
  const auto jump_at = [&](const Eigen::MatrixXd& y, double& worst) {
    double sum = 0.0;
    worst = 0.0;
    const Eigen::MatrixX3d poles = unflatten(y);
    for (const CurvatureConstraint& c : pb.curvatures) {
      double rms = 0.0;
      worst = std::max(worst, curvature_jump(pb.space, poles, c, 1.0 / size, 200, &rms));
      sum += rms * rms;
    }
    for (const PointCurvatureConstraint& c : pb.point_curvatures) {
      const double e = point_curvature_error(pb.space, poles, c, 1.0 / size);
      worst = std::max(worst, e);
      sum += e * e;
    }
    return std::sqrt(sum / static_cast<double>(pb.curvatures.size() + pb.point_curvatures.size()));
  };
  Eigen::MatrixXd best = x;
  double best_max = 0.0;
  double best_jump = jump_at(x, best_max);
  int stalled = 0;
  rep.converged = false;
  for (int it = 1; it <= opt.max_curvature_iterations; ++it) {
    check_keep_going(opt);
    const Eigen::MatrixX3d current = unflatten(x);
    Quadratic step = as.quad;
    for (size_t i = 0; i < pb.curvatures.size(); ++i) {
      try {
        step.blocks.push_back(sample_curvature(pb.space, pb.curvatures[i], current));
      } catch (const InvalidInput& e) {
        throw InvalidInput("curvature constraint " + std::to_string(i) + ": " + e.what());
      }
    }
    for (size_t i = 0; i < pb.point_curvatures.size(); ++i) {
      try {
        step.blocks.push_back(sample_point_curvature(pb.space, pb.point_curvatures[i], current));
      } catch (const InvalidInput& e) {
        throw InvalidInput("point curvature " + std::to_string(i) + ": " + e.what());
      }
    }
    SolveReport inner;
    inner.coupled = true;
    Eigen::MatrixXd next = solve_quadratic(step, opt, inner);
    if (as.nonlinear) next = iterate_nonlinear(pb, opt, as.scales, step, next, inner);
    const double move = (next - x).cwiseAbs().maxCoeff();
    if (!std::isfinite(move)) throw SolveFailure("G2 iterations diverged (poles not finite)");
    // Far from G2 (or where corners ask for two curvatures) a full step can fold the sheet
    // (measured: 44 mm moves on a 6 mm corner blend); at most step_limit of its size, as for
    // the other nonlinear terms. Both ends meet the linear constraints, so the step does too.
    if (move > limit) next = x + (limit / move) * (next - x);
    x = std::move(next);
    double worst = 0.0;
    const double jump = jump_at(x, worst);
    rep.curvature_iterations = it;
    rep.last_step = move;
    if (!pb.point_curvatures.empty()) {
      // A point's curvature is met long before the shape stops moving (the energy still trades
      // the bend against the stretch of w_u, w_v: measured 0.09 mm between two scenes that
      // differ by a rigid motion, both within 1e-5 of the curvature): the answer is where the
      // poles stop moving.
      best = x, best_jump = jump, best_max = worst;
      rep.constraint_samples = inner.constraint_samples;
      rep.constraint_rank = inner.constraint_rank;
      rep.constraint_residual = inner.constraint_residual;
      rep.conflict = inner.conflict;
      if (move <= tol) {
        rep.converged = worst <= opt.curvature_tolerance;
        break;
      }
      continue;
    }
    // What the space can do is done when the jump stops falling (the rows are met in least
    // squares, or only to the fit tolerance): stop after two steps that gain less than 1 %.
    stalled = jump > 0.99 * best_jump ? stalled + 1 : 0;
    if (jump < best_jump) {
      best = x, best_jump = jump, best_max = worst;
      rep.constraint_samples = inner.constraint_samples;
      rep.constraint_rank = inner.constraint_rank;
      rep.constraint_residual = inner.constraint_residual;
      rep.conflict = inner.conflict;
    }
    if (worst <= opt.curvature_tolerance || move <= tol || stalled >= 2) {
      rep.converged = best_max <= opt.curvature_tolerance;
      break;
    }
  }
  rep.curvature_jump = best_max;
  return best;
}

}  // namespace

Quadratic sheet_quadratic(const SheetProblem& pb, const SolveOptions& opt, bool fold_rest,
                          bool force_coupled) {
  validate_problem(pb, opt);
  SolveOptions coupled = opt;
  coupled.force_coupled = opt.force_coupled || force_coupled;
  SolveReport rep;
  if (has_curvature_conditions(pb))
    throw InvalidInput(
        "G2 and point curvature conditions are iterated per sheet: they cannot be part of a joint "
        "or hierarchical "
        "solve (solve that sheet on its own, on a uniform space)");
  Assembled as = assemble(pb, coupled, rep);
  if (as.nonlinear)
    throw InvalidInput(
        "pressure, repellers and shape attractors are iterated per sheet: they cannot be part of "
        "a joint solve (solve that sheet on its own)");
  // Joint solves combine several sheets' f: the rest shape goes into f, as x^T Q x - 2 f^T x.
  if (fold_rest && as.quad.rest.size()) {
    as.quad.f += as.quad.q * as.quad.rest;
    as.quad.rest.resize(0, 0);
  }
  return std::move(as.quad);
}

namespace {

// Multigrid when asked, or in Automatic mode for a large sheet held by its fixed poles alone with
// a coarser level (see SolveOptions::multigrid_from); empty to solve directly. Automatic falls
// back to the direct solve (saying why) when multigrid fails: an energy the fixed poles do not
// hold, or conjugate gradients that stall.
std::optional<SolveResult> solve_by_multigrid(const SheetProblem& pb, const SolveOptions& opt,
                                              std::string& declined) {
  const bool asked = opt.mode == SolveMode::multigrid;
  if (asked && !held_by_fixed_poles_alone(pb))
    throw InvalidInput(
        "multigrid solves a non-rational sheet held by its fixed poles alone (its boundary "
        "conditions); this one has constraints, operators, pressure, a closure or a kept region: "
        "choose another solve mode");
  if (!asked) {
    if (opt.mode != SolveMode::automatic || !held_by_fixed_poles_alone(pb) ||
        !has_coarser_level(pb.space))
      return std::nullopt;
    if (free_unknowns(pb.space.size(), pb.fixed_poles, "the sheet").size() < opt.multigrid_from)
      return std::nullopt;
  }
  MultigridOptions mo;
  mo.keep_going = opt.keep_going;
  try {
    return solve_sheet_multigrid(pb, mo);
  } catch (const SolveFailure& failure) {
    if (asked) throw;
    declined = std::string(" (multigrid declined: ") + failure.what() + ")";
    return std::nullopt;
  }
}

}  // namespace

SolveResult solve_sheet(const SheetProblem& pb, const SolveOptions& opt) {
  const auto start = Clock::now();
  const SolveBudget budget(opt);
  validate_problem(pb, opt);
  std::string declined;
  if (std::optional<SolveResult> mg = solve_by_multigrid(pb, opt, declined)) {
    mg->report.total_seconds = seconds_since(start);
    return std::move(*mg);
  }
  SolveResult result;
  SolveReport& rep = result.report;
  auto t = Clock::now();
  const Assembled as = assemble(pb, opt, rep);
  rep.assemble_seconds = seconds_since(t);
  Eigen::MatrixXd x = solve_quadratic(as.quad, opt, rep);
  if (as.nonlinear) x = iterate_nonlinear(pb, opt, as.scales, as.quad, x, rep);
  if (has_curvature_conditions(pb)) x = iterate_curvature(pb, opt, as, x, rep);
  result.poles = to_poles(x, rep.coupled);
  rep.mode_reason += declined;
  rep.total_seconds = seconds_since(start);
  return result;
}

struct PreparedSheet::State {
  SheetProblem problem;
  SolveOptions options;
  Assembled assembled;
  // Per curve: where it is sampled and its separable samples, so that a moved target costs only
  // evaluations of the target, not of the sheet's basis.
  std::vector<CurveSampling> curve_samplings;
  std::vector<ConstraintSamples> curve_blocks;
  // A second copy of curve_blocks that update() moves into its constraint list and back, each
  // block with the target its right-hand sides were computed for: copying every curve's samples
  // per drag update (and freeing them) was a quarter of a 64 x 64 update. Rebuilt from
  // curve_blocks whenever it was not given back (an exception, a coupled solve, a change()).
  std::vector<ConstraintSamples> lent_blocks;
  std::vector<Eigen::MatrixXd> lent_targets;
  bool lent_ready = false;
  std::unique_ptr<ConstrainedSolve> solver;
  SolveResult result;
};

PreparedSheet::PreparedSheet(const SheetProblem& pb, const SolveOptions& opt) : state_(new State) {
  const auto start = Clock::now();
  const SolveBudget budget(opt);
  validate_problem(pb, opt);
  State& st = *state_;
  st.problem = pb;
  st.options = opt;
  SolveReport& rep = st.result.report;
  auto t = Clock::now();
  st.assembled = assemble(pb, opt, rep, [&](size_t, const CurveConstraint& c) {
    st.curve_samplings.push_back(curve_sampling(pb.space, c));
    st.curve_blocks.push_back(sample_curve(pb.space, c, st.curve_samplings.back()));
    return st.curve_blocks.back();
  });
  rep.assemble_seconds = seconds_since(t);
  if (st.assembled.nonlinear || has_curvature_conditions(pb))
    throw InvalidInput(
        "repellers, shape attractors, pressure, G2 and point curvatures are solved by iteration: "
        "there is no factorization to keep");
  st.solver = std::make_unique<ConstrainedSolve>(st.assembled.quad, opt, rep);
  const Eigen::MatrixXd x = st.solver->solve(st.assembled.quad.f, st.solver->reduced_rhs(), rep);
  st.result.poles = to_poles(x, rep.coupled);
  rep.total_seconds = seconds_since(start);
}

PreparedSheet::~PreparedSheet() = default;
PreparedSheet::PreparedSheet(PreparedSheet&&) noexcept = default;
PreparedSheet& PreparedSheet::operator=(PreparedSheet&&) noexcept = default;

const SolveResult& PreparedSheet::result() const {
  return state_->result;
}

namespace {

// The same constraint matrices up to rounding (a rigidly moved curve keeps its arc-length
// weights only to rounding).
// Blocks [rows_known_from, rows_known_to) were built from b's own rows (moved curves): only their
// weights can differ, so only those are compared (the drag update's hot path).
bool same_samples(const std::vector<ConstraintSamples>& a, const std::vector<ConstraintSamples>& b,
                  size_t rows_known_from, size_t rows_known_to) {
  if (a.size() != b.size()) return false;
  const auto close = [](double x, double y) {
    return std::abs(x - y) <= 1e-12 * std::max(std::abs(x), std::abs(y));
  };
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].weight.size() != b[i].weight.size() || a[i].exact != b[i].exact) return false;
    for (size_t r = 0; r < a[i].weight.size(); ++r)
      if (!close(a[i].weight[r], b[i].weight[r])) return false;
    if (i >= rows_known_from && i < rows_known_to) continue;
    if (a[i].index != b[i].index) return false;
    for (size_t r = 0; r < a[i].coeff.size(); ++r)
      for (Eigen::Index k = 0; k < a[i].coeff[r].size(); ++k)
        if (!close(a[i].coeff[r](k), b[i].coeff[r](k))) return false;
  }
  return true;
}

bool same_space(const SplineSpace& a, const SplineSpace& b) {
  return a.degree_u == b.degree_u && a.degree_v == b.degree_v && a.knots_u == b.knots_u &&
         a.knots_v == b.knots_v && a.weights.size() == b.weights.size() && a.weights == b.weights;
}

bool same_curve_shape(const BSplineCurve& a, const BSplineCurve& b) {
  return a.degree == b.degree && a.knots == b.knots && a.poles.rows() == b.poles.rows() &&
         a.poles.cols() == b.poles.cols();
}

bool same_curve(const CurveConstraint& a, const CurveConstraint& b) {
  return same_curve_shape(a.preimage, b.preimage) && a.preimage.poles == b.preimage.poles &&
         same_curve_shape(a.target, b.target) && a.target.poles == b.target.poles &&
         a.weight == b.weight && a.exact == b.exact;
}

// Everything but the constraints is as prepared: the energy and its assembly can be kept.
void check_same_setup(const SheetProblem& pb, const SheetProblem& moved) {
  const bool same_setup =
      same_space(pb.space, moved.space) && pb.fixed_poles == moved.fixed_poles &&
      pb.energy.alpha == moved.energy.alpha && pb.energy.beta == moved.energy.beta &&
      pb.pde.has_value() == moved.pde.has_value() && (!pb.pde || *pb.pde == *moved.pde) &&
      pb.rest_poles.rows() == moved.rest_poles.rows() && pb.closed_u == moved.closed_u &&
      pb.closed_v == moved.closed_v &&
      (pb.rest_poles.rows() == 0 || pb.rest_poles == moved.rest_poles) &&
      pb.attractors.size() == moved.attractors.size() &&
      pb.directors.size() == moved.directors.size() && moved.repellers.empty() &&
      moved.shape_attractors.empty() && moved.pressure == 0.0 && !has_curvature_conditions(moved) &&
      pb.kept_region.has_value() == moved.kept_region.has_value() &&
      (!pb.kept_region || same_region(*pb.kept_region, *moved.kept_region)) &&
      pb.overhang_energy == moved.overhang_energy;
  if (!same_setup)
    throw InvalidInput(
        "update: only constraints may change (the space, fixed poles, energy, kept region, rest "
        "shape or operators changed): prepare the sheet again");
  for (size_t i = 0; i < pb.attractors.size(); ++i) {
    const Attractor &a = pb.attractors[i], &b = moved.attractors[i];
    if (a.kind != b.kind || a.origin != b.origin || a.direction != b.direction ||
        a.strength != b.strength || !same_region(a.region, b.region))
      throw InvalidInput("update: an attractor changed: prepare the sheet again");
  }
  for (size_t i = 0; i < pb.directors.size(); ++i)
    if (pb.directors[i].direction != moved.directors[i].direction ||
        pb.directors[i].strength != moved.directors[i].strength)
      throw InvalidInput("update: a director changed: prepare the sheet again");
  if (moved.initial_poles != pb.initial_poles)
    throw InvalidInput("update: the start poles changed: prepare the sheet again");
}

}  // namespace

SolveResult PreparedSheet::update(const SheetProblem& moved) {
  const auto start = Clock::now();
  State& st = *state_;
  const SheetProblem& pb = st.problem;
  validate_problem(moved, st.options);
  check_same_setup(pb, moved);
  if (has_coupled_constraints(pb) != has_coupled_constraints(moved))
    throw InvalidInput("update: constraints were added or removed: use change()");
  SolveResult out;
  out.report = st.result.report;
  const CurveSampler moved_curve = [&](size_t i, const CurveConstraint& c) {
    if (i >= pb.curves.size())
      throw InvalidInput("update: constraints were added or removed: use change()");
    const CurveConstraint& was = pb.curves[i];
    if (!same_curve_shape(c.preimage, was.preimage) || c.preimage.poles != was.preimage.poles ||
        !same_curve_shape(c.target, was.target) || c.weight != was.weight || c.exact != was.exact)
      throw InvalidInput("update: a curve's pre-image, knots or weight changed: use change()");
    ConstraintSamples block = std::move(st.lent_blocks[i]);  // same rows; new right-hand sides
    // A target that did not move keeps its right-hand sides (most curves, while one is dragged:
    // re-evaluating them was a sixth of a 64 x 64 drag update).
    if (c.target.poles == st.lent_targets[i]) return block;
    std::vector<bool> kept;
    curve_rhs(c, st.curve_samplings[i], block.rhs, block.weight, kept);
    if (block.weight.size() != block.index.size())
      throw InvalidInput("update: a curve's samples changed: use change()");
    st.lent_targets[i] = c.target.poles;
    return block;
  };
  if (!st.lent_ready) {
    st.lent_blocks = st.curve_blocks;
    st.lent_targets.clear();
    for (const CurveConstraint& c : pb.curves) st.lent_targets.push_back(c.target.poles);
  }
  st.lent_ready = false;  // until the blocks are given back below
  std::vector<ConstraintSamples> blocks =
      sample_constraints(moved, out.report.coupled, moved_curve);
  // sample_constraints puts the points first, then the curves.
  if (!same_samples(blocks, st.assembled.quad.blocks, moved.points.size(),
                    moved.points.size() + moved.curves.size()))
    throw InvalidInput(
        "update: constraints were added, removed or re-placed (not only moved): use change()");
  const Eigen::MatrixXd b = st.solver->reduced_rhs(blocks);
  const Eigen::MatrixXd x = st.solver->solve(st.assembled.quad.f, b, out.report);
  if (!out.report.coupled) {  // coupled solves copied the curves' rows (to_coupled)
    for (size_t i = 0; i < moved.curves.size(); ++i)
      st.lent_blocks[i] = std::move(blocks[moved.points.size() + i]);
    st.lent_ready = true;
  }
  out.poles = to_poles(x, out.report.coupled);
  out.report.assemble_seconds = out.report.reduce_seconds = out.report.factor_seconds = 0.0;
  out.report.total_seconds = seconds_since(start);
  return out;
}

SolveResult PreparedSheet::change(const SheetProblem& changed) {
  const auto start = Clock::now();
  State& st = *state_;
  const SolveBudget budget(st.options);
  validate_problem(changed, st.options);
  check_same_setup(st.problem, changed);
  SolveReport rep;
  if (!st.result.report.coupled && has_coupled_constraints(changed)) {
    // A constraint now couples x, y and z: the unknowns' layout changes, so start over. (The
    // other way round the coupled layout simply stays.)
    *this = PreparedSheet(changed, st.options);
    return state_->result;
  }
  // The energy (and its assembly) stays; curves already sampled are reused, new ones sampled.
  auto t = Clock::now();
  std::vector<CurveSampling> samplings;
  std::vector<ConstraintSamples> curve_blocks;
  const CurveSampler reuse = [&](size_t, const CurveConstraint& c) {
    for (size_t j = 0; j < st.problem.curves.size(); ++j)
      if (same_curve(c, st.problem.curves[j])) {
        samplings.push_back(st.curve_samplings[j]);
        curve_blocks.push_back(st.curve_blocks[j]);
        return curve_blocks.back();
      }
    samplings.push_back(curve_sampling(changed.space, c));
    curve_blocks.push_back(sample_curve(changed.space, c, samplings.back()));
    return curve_blocks.back();
  };
  rep.coupled = st.result.report.coupled;
  st.assembled.quad.blocks = sample_constraints(changed, rep.coupled, reuse);
  rep.assemble_seconds = seconds_since(t);
  // The earlier factor serves a few added rows (ConstrainedSolve decides).
  st.solver =
      std::make_unique<ConstrainedSolve>(st.assembled.quad, st.options, rep, st.solver.get());
  const Eigen::MatrixXd x = st.solver->solve(st.assembled.quad.f, st.solver->reduced_rhs(), rep);
  st.problem = changed;
  st.curve_samplings = std::move(samplings);
  st.curve_blocks = std::move(curve_blocks);
  st.lent_ready = false;
  st.result.poles = to_poles(x, rep.coupled);
  rep.total_seconds = seconds_since(start);
  st.result.report = rep;
  return st.result;
}

}  // namespace varsurf
