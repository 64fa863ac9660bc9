// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/hierarchical_solver.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <tuple>

#include "constrained_solve.hpp"
#include "sheet_assembly.hpp"
#include "solve_limits.hpp"
#include "stopwatch.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_refinement.hpp"
#include "varsurf/core/knot_vector.hpp"

namespace varsurf {

namespace {

using Sparse = Eigen::SparseMatrix<double>;
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// The span (between distinct breakpoints) holding t; the last one for t at the end.
int span_index(const std::vector<double>& knots, int degree, double t) {
  const std::vector<double> bp = breakpoints(knots, degree);
  const int s = static_cast<int>(std::upper_bound(bp.begin(), bp.end(), t) - bp.begin()) - 1;
  return std::clamp(s, 0, static_cast<int>(bp.size()) - 2);
}

// The deepest span under (u, v) that is in its level's region and not refined further.
std::tuple<int, int, int> leaf_at(const HierarchicalSpace& h, double u, double v) {
  for (int k = 0; k < h.levels(); ++k) {
    const int su = span_index(h.layer(k).knots_u, h.layer(k).degree_u, u);
    const int sv = span_index(h.layer(k).knots_v, h.layer(k).degree_v, v);
    if (!h.refined(k, su, sv)) return {k, su, sv};
  }
  return {h.levels() - 1, 0, 0};  // not reached: the last level has nothing refined
}

bool is_boundary_set(const SheetProblem& pb, std::vector<int> fixed) {
  std::vector<int> boundary = boundary_pole_indices(pb.space, pb.closed_u, pb.closed_v);
  std::sort(fixed.begin(), fixed.end());
  fixed.erase(std::unique(fixed.begin(), fixed.end()), fixed.end());
  std::sort(boundary.begin(), boundary.end());
  return fixed == boundary;
}

// The problem on the finest level: the same terms, the start (and rest) shape refined exactly.
SheetProblem finest_problem(const SheetProblem& base, const HierarchicalSpace& h) {
  SheetProblem fine = base;
  fine.space = h.finest();
  fine.initial_poles = h.base_to_finest(base.initial_poles);
  if (base.rest_poles.rows() > 0) fine.rest_poles = h.base_to_finest(base.rest_poles);
  fine.fixed_poles = base.fixed_poles.empty()
                         ? std::vector<int>{}
                         : boundary_pole_indices(fine.space, base.closed_u, base.closed_v);
  return fine;
}

}  // namespace

Eigen::MatrixX3d solve_on_hierarchy(const SheetProblem& base, const HierarchicalSpace& h,
                                    const SolveOptions& opt, SolveReport& rep,
                                    int influence_level) {
  const auto start = Clock::now();
  const SolveBudget budget(opt);
  base.space.validate();
  if (base.space.knots_u != h.layer(0).knots_u || base.space.knots_v != h.layer(0).knots_v ||
      base.space.degree_u != h.layer(0).degree_u || base.space.degree_v != h.layer(0).degree_v)
    throw InvalidInput("the problem's space is not the hierarchy's base");
  if (base.initial_poles.rows() != base.space.size())
    throw InvalidInput("initial poles: one per pole of the base space");
  if (!base.fixed_poles.empty() && !is_boundary_set(base, base.fixed_poles))
    throw InvalidInput(
        "a locally refined sheet can keep its whole boundary, not other fixed poles "
        "(frozen regions need uniform refinement)");
  const SheetProblem fine = finest_problem(base, h);
  if (fine.space.size() > opt.max_unknowns)
    throw ResourceLimit("the refined sheet's finest level has " +
                        std::to_string(fine.space.size()) + " poles, more than the limit of " +
                        std::to_string(opt.max_unknowns) + "; lower MaxDepth");
  check_memory(3LL * fine.space.size(),
               (2LL * fine.space.degree_u + 1) * (2LL * fine.space.degree_v + 1),
               SolveMode::penalty, opt, "the refined sheet's finest level");
  // Separable unless a term couples x, y and z: then one hierarchical system of the dofs shared
  // by the three coordinates instead of one of three times as many unknowns (measured on
  // benchmark 6's 1e-6 case: the coupled system made the local refinement slower than uniform).
  const Quadratic q = sheet_quadratic(fine, opt, /*fold_rest=*/false, /*force_coupled=*/false);
  const bool coupled = q.q.rows() != fine.space.size();
  const int per_pole = coupled ? 3 : 1;
  // x = x_s + B d: the displacement d lives in the hierarchical space.
  const Sparse b = coupled ? kron_identity3(h.to_finest()) : h.to_finest();
  const RowSparse br = b;
  const Eigen::MatrixXd xs =
      coupled ? flatten(fine.initial_poles) : Eigen::MatrixXd(fine.initial_poles);
  Quadratic hq;
  const Sparse qb = q.q * b;
  const Sparse bt = b.transpose();
  hq.q = bt * qb;
  // With a rest shape the energy is that of x - rest: the displacement from the start is what
  // it sees (exactly zero when the start is the rest shape, whatever Q's conditioning).
  hq.f = b.transpose() * (q.f - q.q * (q.rest.size() ? Eigen::MatrixXd(xs - q.rest) : xs));
  const Eigen::Index m = b.cols();
  hq.x0 = Eigen::MatrixXd::Zero(m, xs.cols());
  // A degree of freedom that moves a fixed (boundary) pole is held at zero: its function is then
  // one of the boundary row's, and the boundary curve stays.
  hq.fixed.assign(static_cast<size_t>(m), false);
  for (int col = 0; col < b.outerSize(); ++col) {
    if (h.dofs()[static_cast<size_t>(col / per_pole)].level < influence_level)
      hq.fixed[static_cast<size_t>(col)] = true;  // outside the region of influence's levels
    for (Sparse::InnerIterator it(b, col); it; ++it)
      if (q.fixed[static_cast<size_t>(it.row())] && std::abs(it.value()) > 1e-14)
        hq.fixed[static_cast<size_t>(col)] = true;
  }
  for (const ConstraintSamples& block : q.blocks) {
    if (block.coupled() != coupled)
      throw SolveFailure("hierarchical solve: constraint rows in the wrong layout");
    ConstraintSamples out;
    out.exact = block.exact;
    out.weight = block.weight;
    out.rhs.resize(block.rows(), block.rhs.cols());
    for (int r = 0; r < block.rows(); ++r) {
      Eigen::SparseVector<double> row(m);
      Eigen::RowVectorXd shift = Eigen::RowVectorXd::Zero(xs.cols());
      const std::vector<int>& cols = block.index[static_cast<size_t>(r)];
      for (size_t k = 0; k < cols.size(); ++k) {
        const double a = block.coeff[static_cast<size_t>(r)](static_cast<Eigen::Index>(k));
        row += a * Eigen::SparseVector<double>(br.row(cols[k]).transpose());
        shift += a * xs.row(cols[k]);
      }
      std::vector<int> index;
      Eigen::VectorXd coeff(row.nonZeros());
      Eigen::Index n = 0;
      for (Eigen::SparseVector<double>::InnerIterator it(row); it; ++it, ++n) {
        index.push_back(static_cast<int>(it.index()));
        coeff(n) = it.value();
      }
      out.index.push_back(std::move(index));
      out.coeff.push_back(std::move(coeff));
      out.rhs.row(r) = block.rhs.row(r) - shift;
    }
    hq.blocks.push_back(std::move(out));
  }
  rep.coupled = coupled;
  const ConstrainedSolve solver(hq, opt, rep);
  const Eigen::MatrixXd d = solver.solve(hq.f, solver.reduced_rhs(), rep);
  rep.total_seconds = seconds_since(start);  // as solve_sheet's: assembly, reduction, solve
  return coupled ? unflatten(xs + b * d) : Eigen::MatrixX3d(xs + b * d);
}

HierarchicalResult solve_hierarchical(const SheetProblem& base, const HierarchicalOptions& ho,
                                      const SolveOptions& opt) {
  const auto start = Clock::now();
  const SolveBudget budget(opt);
  if (!(ho.tolerance > 0.0) || !std::isfinite(ho.tolerance) || ho.max_depth < 0 ||
      ho.max_depth > 12 || ho.samples < 2 || ho.influence_level < 0 ||
      ho.influence_level > ho.max_depth)
    throw InvalidInput(
        "hierarchical refinement needs a positive tolerance, a depth of 0..12 and "
        "at least 2 samples per curve");
  HierarchicalSpace h(base.space);
  for (const RefineBox& box : ho.manual) {
    if (box.level < 0 || box.level >= ho.max_depth)
      throw InvalidInput("a manual refinement box names level " + std::to_string(box.level) +
                         ": refinable levels are 0 to " + std::to_string(ho.max_depth - 1));
    if (!(box.u0 < box.u1) || !(box.v0 < box.v1))
      throw InvalidInput("a manual refinement box needs u0 < u1 and v0 < v1");
    // Level by level down to the box's: the spans under it and, as for automatic refinement, a
    // ring of neighbours (finer functions need a patch their whole support fits in).
    for (int level = 0; level <= box.level; ++level) {
      const SplineSpace& ls = h.layer(level);
      const int r = std::max(1, std::max(ls.degree_u, ls.degree_v) / 2);
      const int u0 = span_index(ls.knots_u, ls.degree_u, box.u0) - r;
      const int u1 = span_index(ls.knots_u, ls.degree_u, box.u1) + r;
      const int v0 = span_index(ls.knots_v, ls.degree_v, box.v0) - r;
      const int v1 = span_index(ls.knots_v, ls.degree_v, box.v1) + r;
      for (int i = std::max(0, u0); i <= std::min(u1, h.spans_u(level) - 1); ++i)
        for (int j = std::max(0, v0); j <= std::min(v1, h.spans_v(level) - 1); ++j)
          if (h.in_region(level, i, j)) h.refine(level, i, j);
    }
  }
  HierarchicalResult result;
  HierarchicalReport& rep = result.report;
  while (true) {
    check_keep_going(opt);
    rep.solve = SolveReport();
    result.poles = solve_on_hierarchy(base, h, opt, rep.solve, ho.influence_level);
    result.space = h.finest();
    // Measure each curve (and point); the leaf spans under the samples that are off are refined.
    std::set<std::tuple<int, int, int>> to_refine;
    const auto mark = [&](double u, double v) {
      const auto [k, su, sv] = leaf_at(h, u, v);
      if (k >= ho.max_depth) return;
      // With the span, its neighbours within half a support: finer functions need a patch
      // their whole support fits in (a lone span holds none).
      const int r = std::max(1, std::max(h.layer(k).degree_u, h.layer(k).degree_v) / 2);
      for (int di = -r; di <= r; ++di)
        for (int dj = -r; dj <= r; ++dj) {
          const int i = su + di, j = sv + dj;
          if (i < 0 || j < 0 || i >= h.spans_u(k) || j >= h.spans_v(k)) continue;
          if (h.in_region(k, i, j)) {
            if (!h.refined(k, i, j)) to_refine.insert({k, i, j});
            continue;
          }
          // Outside this level's region: the coarser leaf there is refined first.
          const std::vector<double> bu = breakpoints(h.layer(k).knots_u, h.layer(k).degree_u);
          const std::vector<double> bv = breakpoints(h.layer(k).knots_v, h.layer(k).degree_v);
          const auto [lk, li, lj] =
              leaf_at(h, 0.5 * (bu[static_cast<size_t>(i)] + bu[static_cast<size_t>(i + 1)]),
                      0.5 * (bv[static_cast<size_t>(j)] + bv[static_cast<size_t>(j + 1)]));
          if (lk < ho.max_depth) to_refine.insert({lk, li, lj});
        }
    };
    const auto sheet_at = [&](double u, double v) -> Eigen::Vector3d {
      return evaluate_surface(result.space, result.poles, u, v, 0).row(0).transpose();
    };
    rep.max_deviation.assign(base.curves.size(), 0.0);
    double worst = 0.0;
    for (size_t c = 0; c < base.curves.size(); ++c) {
      const CurveConstraint& cc = base.curves[c];
      for (int s = 0; s < ho.samples; ++s) {
        const double t =
            cc.preimage.first() + (cc.preimage.last() - cc.preimage.first()) * s / (ho.samples - 1);
        const Eigen::Vector2d uv = cc.preimage.evaluate(t);
        const double u = std::clamp(uv(0), result.space.u_first(), result.space.u_last());
        const double v = std::clamp(uv(1), result.space.v_first(), result.space.v_last());
        const double dev = (sheet_at(u, v) - cc.target.evaluate(t)).norm();
        rep.max_deviation[c] = std::max(rep.max_deviation[c], dev);
        if (dev > ho.tolerance && ho.automatic) mark(u, v);
      }
      worst = std::max(worst, rep.max_deviation[c]);
    }
    for (const PointConstraint& p : base.points) {  // a point frozen out of reach refines too
      const double dev = (sheet_at(p.u, p.v) - p.target).norm();
      worst = std::max(worst, dev);
      if (dev > ho.tolerance && ho.automatic) mark(p.u, p.v);
    }
    rep.round_error.push_back(worst);
    rep.round_dofs.push_back(h.dof_count());
    rep.met = worst <= ho.tolerance;
    if (rep.met || to_refine.empty()) break;
    for (const auto& [k, su, sv] : to_refine)
      if (h.in_region(k, su, sv)) h.refine(k, su, sv);
  }
  for (int k = 0; k + 1 < h.levels(); ++k) {
    const std::vector<double> bu = breakpoints(h.layer(k).knots_u, h.layer(k).degree_u);
    const std::vector<double> bv = breakpoints(h.layer(k).knots_v, h.layer(k).degree_v);
    for (int i = 0; i < h.spans_u(k); ++i)
      for (int j = 0; j < h.spans_v(k); ++j)
        if (h.refined(k, i, j))
          rep.refined.push_back({k, bu[static_cast<size_t>(i)], bu[static_cast<size_t>(i + 1)],
                                 bv[static_cast<size_t>(j)], bv[static_cast<size_t>(j + 1)]});
  }
  rep.depth = h.levels() - 1;
  rep.dofs = h.dof_count();
  rep.export_poles = h.finest().size();
  rep.total_seconds = seconds_since(start);
  return result;
}

}  // namespace varsurf
