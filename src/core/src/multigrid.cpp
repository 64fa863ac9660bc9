// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/multigrid.hpp"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <string>

#include "free_block.hpp"
#include "solve_limits.hpp"
#include "stopwatch.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_refinement.hpp"
#include "varsurf/core/knot_vector.hpp"
#include "varsurf/core/pde_energy.hpp"
#include "varsurf/core/thin_plate_energy.hpp"

namespace varsurf {

namespace {

using Sparse = Eigen::SparseMatrix<double>;
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;
// x, y and z of a pole side by side: the smoother reads a neighbour's three coordinates at once
// (column-major N x 3 storage made the sweeps 30 % of a 259 x 259 solve).
using Rows3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

// Every other breakpoint of a clamped vector with simple interior knots and an even span count;
// empty when it cannot be halved.
std::vector<double> halved(const std::vector<double>& knots, int degree) {
  const std::vector<double> br = breakpoints(knots, degree);
  const size_t spans = br.size() - 1;
  if (spans < 4 || spans % 2 != 0) return {};
  if (knots.size() != spans - 1 + 2 * static_cast<size_t>(degree + 1))
    return {};  // a multiple knot
  std::vector<double> out(static_cast<size_t>(degree + 1), br.front());
  for (size_t k = 2; k + 1 < br.size(); k += 2) out.push_back(br[k]);
  out.insert(out.end(), static_cast<size_t>(degree + 1), br.back());
  return out;
}

struct Level {
  Sparse a;  // the level's matrix on its free unknowns (symmetric: column i is row i)
  Sparse p;  // prolongation from the next coarser level's free unknowns to these
  Eigen::VectorXd inverse_diagonal;
};

// Symmetric Gauss-Seidel sweeps on a x = b (x updated in place). The matrix is symmetric, so
// its column-major storage is read as rows (no row-major copy of every level).
void smooth(const Level& l, const Rows3& b, Rows3& x, int sweeps) {
  const Eigen::Index n = l.a.rows();
  const int* outer = l.a.outerIndexPtr();
  const int* inner = l.a.innerIndexPtr();
  const double* values = l.a.valuePtr();
  double* xs = x.data();
  const double* bs = b.data();
  for (int s = 0; s < sweeps; ++s)
    for (int pass = 0; pass < 2; ++pass)
      for (Eigen::Index k = 0; k < n; ++k) {
        const Eigen::Index i = pass == 0 ? k : n - 1 - k;
        double sx = bs[3 * i], sy = bs[3 * i + 1], sz = bs[3 * i + 2];
        for (int e = outer[i]; e < outer[i + 1]; ++e) {
          const int c = inner[e];
          if (c == i) continue;
          const double v = values[e];
          sx -= v * xs[3 * c];
          sy -= v * xs[3 * c + 1];
          sz -= v * xs[3 * c + 2];
        }
        const double d = l.inverse_diagonal(i);
        xs[3 * i] = sx * d;
        xs[3 * i + 1] = sy * d;
        xs[3 * i + 2] = sz * d;
      }
}

struct Hierarchy {
  std::vector<Level> levels;
  Eigen::SimplicialLDLT<Sparse> coarsest;
  int sweeps = 2;

  Rows3 cycle(size_t l, const Rows3& r) const {
    if (l + 1 == levels.size()) return coarsest.solve(Eigen::MatrixX3d(r));
    const Level& lv = levels[l];
    Rows3 x = Rows3::Zero(r.rows(), 3);
    smooth(lv, r, x, sweeps);
    const Rows3 residual = r - lv.a * x;
    x += lv.p * cycle(l + 1, lv.p.transpose() * residual);
    smooth(lv, r, x, sweeps);
    return x;
  }
};

}  // namespace

Eigen::MatrixX3d solve_multigrid(const SplineSpace& space, const Sparse& q,
                                 const Eigen::MatrixX3d& f, const Eigen::MatrixX3d& x0,
                                 const std::vector<int>& fixed, const MultigridOptions& o,
                                 MultigridReport* report) {
  space.validate();
  if (space.rational()) throw InvalidInput("multigrid: the sheet must be non-rational");
  const int n = space.size();
  if (q.rows() != n || q.cols() != n || f.rows() != n || x0.rows() != n)
    throw InvalidInput("multigrid: the matrix, right-hand side and start must match the space");
  if (o.smoothing < 1 || o.smoothing > 100 || o.coarsest_poles < 1 || o.max_iterations < 1 ||
      o.max_iterations > 100000 || !(o.tolerance > 0.0 && o.tolerance < 1.0))
    throw InvalidInput(
        "multigrid: smoothing 1..100 sweeps, a coarsest size above 0, 1..100000 "
        "iterations and a tolerance in (0, 1)");
  const auto started = Clock::now();
  const FreeUnknowns unknowns = free_unknowns(n, fixed, "multigrid");
  const std::vector<int>& free = unknowns.free;
  const Eigen::Index nf = static_cast<Eigen::Index>(free.size());
  if (nf == 0) return x0;
  // The fine system on the free poles: Q_FF x_F = f_F - Q_FX x0_X.
  Eigen::MatrixX3d held = x0;
  for (int k : free) held.row(k).setZero();
  const Eigen::MatrixX3d right = f - q * held;
  Rows3 b(nf, 3);
  for (Eigen::Index k = 0; k < nf; ++k) b.row(k) = right.row(free[static_cast<size_t>(k)]);
  Hierarchy h;
  h.sweeps = o.smoothing;
  std::vector<double> ku = space.knots_u, kv = space.knots_v;
  std::vector<int> cols = free;  // the current level's free unknowns as pole indices of its space
  int nv = space.nv();
  long long stored = 0;
  // Each level's matrix is made in place (Eigen 3.4's sparse matrices copy where they could
  // move, and the fine one is most of the memory).
  h.levels.reserve(16);
  h.levels.emplace_back();
  h.levels.back().a = free_block(q, unknowns);
  while (true) {
    Level& lv = h.levels.back();
    lv.inverse_diagonal = lv.a.diagonal().cwiseInverse();
    if (!lv.inverse_diagonal.allFinite())
      throw SolveFailure("multigrid: the energy has a zero diagonal on a free pole");
    stored += lv.a.nonZeros();
    const std::vector<double> cu = halved(ku, space.degree_u), cv = halved(kv, space.degree_v);
    if (lv.a.rows() <= o.coarsest_poles || cu.empty() || cv.empty()) break;
    // Prolongation: kron(Tu, Tv) from the coarse space's poles to this level's, its rows
    // restricted to this level's free unknowns, its columns to the coarse poles they reach.
    const Sparse tu = refinement_matrix(cu, space.degree_u, ku);
    const Sparse tv = refinement_matrix(cv, space.degree_v, kv);
    const int nvc = static_cast<int>(tv.cols()), nc = static_cast<int>(tu.cols()) * nvc;
    const RowSparse tur = tu, tvr = tv;
    std::vector<int> used(static_cast<size_t>(nc), -1);
    std::vector<int> coarse_cols;
    std::vector<Eigen::Triplet<double>> pt;
    for (size_t r = 0; r < cols.size(); ++r) {
      const int i = cols[r] / nv, j = cols[r] % nv;
      for (RowSparse::InnerIterator a_it(tur, i); a_it; ++a_it)
        for (RowSparse::InnerIterator b_it(tvr, j); b_it; ++b_it) {
          const int c = static_cast<int>(a_it.col()) * nvc + static_cast<int>(b_it.col());
          if (used[static_cast<size_t>(c)] < 0) {
            used[static_cast<size_t>(c)] = static_cast<int>(coarse_cols.size());
            coarse_cols.push_back(c);
          }
          pt.emplace_back(static_cast<int>(r), used[static_cast<size_t>(c)],
                          a_it.value() * b_it.value());
        }
    }
    lv.p = Sparse(static_cast<Eigen::Index>(cols.size()),
                  static_cast<Eigen::Index>(coarse_cols.size()));
    lv.p.setFromTriplets(pt.begin(), pt.end());
    stored += lv.p.nonZeros();
    // P^T (A P) with every operand column-major: Eigen's mixed-storage product converted the
    // whole fine matrix first.
    Sparse coarse;
    {
      const Sparse ap = lv.a * lv.p;
      const Sparse p_t = lv.p.transpose();
      coarse = p_t * ap;
    }
    h.levels.emplace_back();  // may reallocate: lv is not used below
    h.levels.back().a.swap(coarse);
    cols = coarse_cols;
    ku = cu;
    kv = cv;
    nv = nvc;
  }
  h.coarsest.compute(h.levels.back().a);
  // A pivot at rounding level is a direction the energy does not determine: the fixed poles do
  // not hold the sheet (a thin plate's affine motions, a PDE's harmonic ones), and conjugate
  // gradients would not find the answer nearest the start the direct solve gives.
  if (h.coarsest.info() != Eigen::Success ||
      !(h.coarsest.vectorD().minCoeff() > 1e-12 * h.coarsest.vectorD().cwiseAbs().maxCoeff()))
    throw SolveFailure(
        "multigrid: the coarsest level is singular (the fixed poles do not hold the sheet)");
  const double setup = seconds_since(started);

  // Conjugate gradients for x, y and z in lockstep (each its own step lengths), one V-cycle of
  // the three residuals a step: the cycle's sweeps cost as much for three columns as for one.
  const auto solving = Clock::now();
  // From the start's free poles (a re-solve after a small change starts near its answer); the
  // residual is measured against the larger of the right-hand side and the start's pull.
  Rows3 x(nf, 3);
  for (Eigen::Index k = 0; k < nf; ++k) x.row(k) = x0.row(free[static_cast<size_t>(k)]);
  const Rows3 pull = h.levels.front().a * x;
  Rows3 r = b - pull;
  const Eigen::RowVector3d norm = b.colwise().norm().cwiseMax(pull.colwise().norm());
  auto relative = [&](const Rows3& res) {
    double worst = 0.0;
    for (int c = 0; c < 3; ++c)
      if (norm(c) > 0.0) worst = std::max(worst, res.col(c).norm() / norm(c));
    return worst;
  };
  Rows3 z = h.cycle(0, r), d = z;
  Eigen::RowVector3d rz = (r.array() * z.array()).colwise().sum();
  int it = 0;
  double rel = relative(r);
  for (; it < o.max_iterations && rel > o.tolerance; ++it) {
    if (o.keep_going && !o.keep_going()) throw Cancelled("the solve was cancelled");
    check_deadline();
    const Rows3 ad = h.levels.front().a * d;
    const Eigen::RowVector3d dad = (d.array() * ad.array()).colwise().sum();
    for (int c = 0; c < 3; ++c) {
      const double alpha = dad(c) > 0.0 ? rz(c) / dad(c) : 0.0;  // a column already solved
      x.col(c) += alpha * d.col(c);
      r.col(c) -= alpha * ad.col(c);
    }
    rel = relative(r);
    if (rel <= o.tolerance) {
      ++it;
      break;
    }
    z = h.cycle(0, r);
    const Eigen::RowVector3d rz_next = (r.array() * z.array()).colwise().sum();
    for (int c = 0; c < 3; ++c)
      d.col(c) = z.col(c) + (rz(c) != 0.0 ? rz_next(c) / rz(c) : 0.0) * d.col(c);
    rz = rz_next;
  }
  if (rel > o.tolerance)
    throw SolveFailure("multigrid: conjugate gradients stopped at a relative residual of " +
                       std::to_string(rel) + " after " + std::to_string(it) + " steps");
  if (report) {
    report->iterations = it;
    report->residual = rel;
  }
  Eigen::MatrixX3d out = x0;
  for (Eigen::Index k = 0; k < nf; ++k) out.row(free[static_cast<size_t>(k)]) = x.row(k);
  if (report) {
    report->levels = static_cast<int>(h.levels.size());
    report->setup_seconds = setup;
    report->solve_seconds = seconds_since(solving);
    report->stored_entries = stored;
  }
  return out;
}

bool held_by_fixed_poles_alone(const SheetProblem& pb) {
  return pb.points.empty() && pb.curves.empty() && pb.tangents.empty() && pb.normals.empty() &&
         pb.plane_points.empty() && pb.line_points.empty() && pb.ribbons.empty() &&
         pb.curvatures.empty() && pb.point_curvatures.empty() && pb.attractors.empty() &&
         pb.directors.empty() && pb.repellers.empty() && pb.shape_attractors.empty() &&
         pb.pressure == 0.0 && !pb.closed_u && !pb.closed_v && !pb.kept_region &&
         !pb.space.rational();
}

bool has_coarser_level(const SplineSpace& space) {
  return !halved(space.knots_u, space.degree_u).empty() &&
         !halved(space.knots_v, space.degree_v).empty();
}

SolveResult solve_sheet_multigrid(const SheetProblem& pb, const MultigridOptions& o,
                                  MultigridReport* report) {
  if (!held_by_fixed_poles_alone(pb))
    throw InvalidInput(
        "multigrid: only a non-rational sheet held by its fixed poles (its boundary conditions) "
        "is solved by multigrid; solve the others with solve_sheet");
  pb.space.validate();
  if (pb.initial_poles.rows() != pb.space.size() || !pb.initial_poles.allFinite())
    throw InvalidInput("multigrid: the start poles do not match the space (or are not finite)");
  const auto started = Clock::now();
  const Sparse q =
      pb.pde ? assemble_pde(pb.space, *pb.pde) : assemble_thin_plate(pb.space, pb.energy);
  Eigen::MatrixX3d f = Eigen::MatrixX3d::Zero(pb.space.size(), 3);
  if (pb.rest_poles.rows() != 0) {
    if (pb.rest_poles.rows() != pb.space.size() || !pb.rest_poles.allFinite())
      throw InvalidInput("multigrid: the rest poles do not match the space (or are not finite)");
    f = q * pb.rest_poles;
  }
  const double assemble = seconds_since(started);
  SolveResult out;
  MultigridReport own;
  MultigridReport& mg = report ? *report : own;
  out.poles = solve_multigrid(pb.space, q, f, pb.initial_poles, pb.fixed_poles, o, &mg);
  SolveReport& rep = out.report;
  rep.assemble_seconds = assemble;
  rep.unknowns = free_unknowns(pb.space.size(), pb.fixed_poles, "multigrid").size();
  rep.mode = SolveMode::multigrid;
  rep.mode_reason =
      "multigrid: " + std::to_string(rep.unknowns) +
      " free poles held by fixed poles alone, conjugate gradients preconditioned on " +
      std::to_string(mg.levels) + " B-spline levels";
  rep.inner_iterations = mg.iterations;
  rep.kkt_residual = mg.residual;
  rep.factor_seconds = mg.setup_seconds;
  rep.solve_seconds = mg.solve_seconds;
  rep.total_seconds = seconds_since(started);
  return out;
}

}  // namespace varsurf
