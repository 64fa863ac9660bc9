// SPDX-License-Identifier: LGPL-2.1-or-later
#include "varsurf/core/triangular_surface.hpp"

#include <Eigen/Geometry>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SVD>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "serial_openmp.hpp"
#include "stopwatch.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/operator_terms.hpp"
#include "varsurf/core/triangle_domain.hpp"
#include "varsurf/core/triangle_g1.hpp"
#include "varsurf/core/triangular_energy.hpp"

#ifdef VARSURF_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

namespace varsurf {

namespace {

using Sparse = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

void check_options(const TriangularProblem& p) {
  const auto non_negative = [](double x) { return std::isfinite(x) && x >= 0.0; };
  if (!non_negative(p.stretch) || !non_negative(p.bend) || !(p.stretch + p.bend > 0.0))
    throw InvalidInput("the stretch and bend weights must be non-negative numbers, not both 0");
  if (!(std::isfinite(p.g1_weight) && p.g1_weight > 0.0))
    throw InvalidInput("the G1 weight must be a positive number");
  if (!(std::isfinite(p.border_angle) && p.border_angle < 2.0 * M_PI) || p.border_angle == 0.0)
    throw InvalidInput(
        "the border angle must lie in (0, 2 pi) radians, or be negative for the "
        "angle the mesh spans");
  if (p.nonlinear_iterations < 1 || p.nonlinear_iterations > 1000 ||
      !(std::isfinite(p.nonlinear_tolerance) && p.nonlinear_tolerance > 0.0))
    throw InvalidInput("the operators' Gauss-Newton steps must be 1..1000, their tolerance > 0");
  if (p.g1_rounds < 0 || p.g1_rounds > 1000)
    throw InvalidInput("the G1 rounds must lie in 0..1000");
  if (p.cg_above < 0 || p.cg_iterations < 1 || !(p.cg_tolerance > 0.0 && p.cg_tolerance < 1.0))
    throw InvalidInput("CG needs a threshold >= 0, iterations >= 1 and a tolerance in (0, 1)");
  if (!(std::isfinite(p.angle_tolerance) && p.angle_tolerance > 0.0))
    throw InvalidInput("the angle tolerance must be a positive number of degrees");
  if (p.angle_samples < 2 || p.angle_samples > 100000)
    throw InvalidInput("an edge's angle takes 2 to 100000 samples");
}

// One scalar row over the 3 N coordinates (column c N + point): sum over local points l and
// coordinates c of coefficient(l) * axis(c).
struct Row {
  std::vector<std::pair<int, double>> terms;  // (coordinate column, value)
  double rhs = 0.0;
};

Row row_of(const std::vector<int>& control, const Eigen::VectorXd& coefficient,
           const Eigen::Vector3d& axis, int count, double rhs) {
  Row r;
  r.rhs = rhs;
  for (int l = 0; l < coefficient.size(); ++l)
    for (int c = 0; c < 3; ++c)
      if (coefficient(l) != 0.0 && axis(c) != 0.0)
        r.terms.push_back({c * count + control[l], coefficient(l) * axis(c)});
  return r;
}

// Two unit vectors perpendicular to d and to each other.
std::array<Eigen::Vector3d, 2> perpendiculars(const Eigen::Vector3d& d) {
  const Eigen::Vector3d u = d.unitOrthogonal();
  return {u, d.cross(u).normalized()};
}

// The free points' system and what solves it: per coordinate (the energy's matrix, the same for x,
// y and z) or, when operators couple the coordinates, as one matrix of 3 nf unknowns. Vectors
// cross it coordinate-major (x of every free point, then y, then z), which is also an nf x 3
// matrix's storage.
struct Factor {
#ifdef VARSURF_HAVE_CHOLMOD
  Eigen::CholmodDecomposition<Sparse> direct;
#else
  Eigen::SimplicialLLT<Sparse> direct;
#endif
  Eigen::ConjugateGradient<Sparse, Eigen::Lower | Eigen::Upper, Eigen::IncompleteCholesky<double>>
      cg;
  bool use_cg = false;
  bool flat = false;  // one 3 nf system
  int nf = 0;
  int iterations = 0;
  double error = 0.0;

  void compute(const Sparse& k) {
    SerialOpenMp serial;
    if (use_cg) {
      cg.compute(k);
      if (cg.info() != Eigen::Success)
        throw SolveFailure("the triangular surface's preconditioner could not be built");
      return;
    }
    direct.compute(k);
    if (direct.info() != Eigen::Success)
      throw SolveFailure(
          "the triangular surface's system is singular: nothing holds it in place; interpolate "
          "the mesh's vertices or add point constraints");
  }
  // Solves with the factored matrix for each column of b (as many rows as it).
  Eigen::MatrixXd columns(const Eigen::MatrixXd& b) {
    SerialOpenMp serial;
    if (!use_cg) return direct.solve(b);
    Eigen::MatrixXd x(b.rows(), b.cols());
    for (int c = 0; c < b.cols(); ++c) {
      x.col(c) = cg.solve(b.col(c));
      iterations = std::max(iterations, static_cast<int>(cg.iterations()));
      error = std::max(error, cg.error());
    }
    return x;
  }
  // The free points for right-hand side b (nf x 3).
  Eigen::MatrixX3d points(const Eigen::MatrixX3d& b) {
    if (!flat) return columns(b);
    const Eigen::VectorXd x = columns(Eigen::Map<const Eigen::VectorXd>(b.data(), 3 * nf));
    return Eigen::Map<const Eigen::MatrixX3d>(x.data(), nf, 3);
  }
  // Solves for each column of b (3 nf rows, coordinate-major).
  Eigen::MatrixXd coordinates(const Eigen::MatrixXd& b) {
    if (flat) return columns(b);
    Eigen::MatrixXd x(b.rows(), b.cols());
    for (int a = 0; a < 3; ++a) x.middleRows(a * nf, nf) = columns(b.middleRows(a * nf, nf));
    return x;
  }
};

}  // namespace

std::vector<double> edge_angles(const TriangleNet& net,
                                const std::vector<TriangularBezier>& patches, int samples) {
  std::vector<double> out;
  for (const NetEdge& e : net.edges) {
    if (e.right < 0) continue;
    out.push_back(shared_edge_angle(patches.at(e.left), e.left_corners[0], e.left_corners[1],
                                    patches.at(e.right), e.right_corners[0], e.right_corners[1],
                                    samples) *
                  180.0 / M_PI);
  }
  return out;
}

TriangularResult solve_triangular(const TriangularProblem& problem) {
  check_options(problem);
  // The energy and the G1 rows do not change under translation: something must fix it.
  const bool held = problem.interpolate_vertices || !problem.fixed_edges.empty() ||
                    std::any_of(problem.constraints.begin(), problem.constraints.end(),
                                [](const TriangularConstraint& c) {
                                  return c.kind == TriangularConstraint::Kind::point;
                                });
  if (!held)
    throw InvalidInput(
        "nothing holds the triangular surface in place; interpolate the mesh's "
        "vertices or add a point constraint");
  const auto t0 = Clock::now();
  TriangularResult result;
  TriangularReport& report = result.report;
  const TriangleNet net = make_triangle_net(problem.vertices, problem.triangles, problem.degree);
  const int n = net.degree;
  const int count = net.control_count;
  const int tcount = static_cast<int>(net.triangles.size());
  const int vcount = static_cast<int>(net.vertices.rows());
  report.patches = tcount;
  report.control_points = count;
  report.flipped = net.flipped;

  // The start: every patch flat on its triangle (its points at (i V1 + j V2 + k V3) / n).
  Eigen::MatrixX3d start(count, 3);
  for (int t = 0; t < tcount; ++t)
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const auto& c = net.triangles[t];
        start.row(net.control[t][triangle_index(n, i, j)]) =
            (i * net.vertices.row(c[0]) + j * net.vertices.row(c[1]) +
             (n - i - j) * net.vertices.row(c[2])) /
            n;
      }

  for (int v = 0; v < vcount; ++v) start.row(v) = net.vertices.row(v);  // exactly, not (n V) / n

  // Energy: per patch over its domain triangle: the mesh triangle itself laid flat, or (their eq.
  // 25) the equilateral triangle of its area, on which the stretch term does not depend on the
  // size and the bend term goes as 1 / side^2.
  const TriangleEnergy unit = triangle_energy(n, 1.0);
  Triplets q_terms;
  for (int t = 0; t < tcount; ++t) {
    const auto [a, b, c] = domain_corners(net, t, problem.equilateral_domain);
    Eigen::MatrixXd local;
    if (problem.equilateral_domain) {  // one matrix for all, scaled (see triangle_energy)
      local = problem.stretch * unit.stretch + problem.bend / (b - a).squaredNorm() * unit.bend;
    } else {
      const TriangleEnergy own = triangle_energy(n, a, b, c);
      local = problem.stretch * own.stretch + problem.bend * own.bend;
    }
    for (int r = 0; r < local.rows(); ++r)
      for (int s = 0; s < local.cols(); ++s)
        q_terms.emplace_back(net.control[t][r], net.control[t][s], local(r, s));
  }
  Sparse q(count, count);
  q.setFromTriplets(q_terms.begin(), q_terms.end());

  // G1 rows (per coordinate) over the control points.
  Triplets f_terms;
  int f_rows = 0;
  if (problem.g1) {
    std::vector<G1Weights> weights(vcount);
    std::vector<bool> inner_edge(vcount, false);
    for (const NetEdge& e : net.edges)
      if (e.right >= 0) inner_edge[e.a] = inner_edge[e.b] = true;
    for (int v = 0; v < vcount; ++v) {
      if (!inner_edge[v]) continue;
      const double angle = problem.border_angle < 0.0 ? net.angle[v] : problem.border_angle;
      try {
        weights[v] = g1_weights(net.patches_at[v], net.border[v], angle);
      } catch (const InvalidInput& e) {
        throw InvalidInput("vertex " + std::to_string(v) + " cannot be made G1: " + e.what() +
                           "; remesh around it or turn G1 off");
      }
    }
    for (int ei = 0; ei < static_cast<int>(net.edges.size()); ++ei) {
      const NetEdge& e = net.edges[ei];
      if (e.right < 0) continue;
      const Eigen::MatrixXd rows =
          g1_edge_equations(n, weights[e.a], weights[e.b], problem.approximate_g1);
      std::vector<int> columns = net.edge_points(ei, e.a);
      for (const int c : net.edge_row(ei, e.left, e.a)) columns.push_back(c);
      for (const int c : net.edge_row(ei, e.right, e.a)) columns.push_back(c);
      for (int r = 0; r < rows.rows(); ++r, ++f_rows)
        for (int c = 0; c < rows.cols(); ++c)
          if (rows(r, c) != 0.0) f_terms.emplace_back(f_rows, columns[c], rows(r, c));
    }
  }
  Sparse f(f_rows, count);
  f.setFromTriplets(f_terms.begin(), f_terms.end());
  report.g1_rows = f_rows;

  // Fixed edges: their points replace the start's and are not solved for; two edges that end at
  // one vertex must agree on where it goes.
  const double size =
      (net.vertices.colwise().maxCoeff() - net.vertices.colwise().minCoeff()).norm();
  std::vector<bool> prescribed(count, false);
  std::vector<int> placed_by(vcount, -1);
  for (std::size_t ei = 0; ei < problem.fixed_edges.size(); ++ei) {
    const FixedEdge& fe = problem.fixed_edges[ei];
    const std::string name = "fixed edge " + std::to_string(ei);
    const int e =
        fe.from >= 0 && fe.to >= 0 && fe.from < vcount && fe.to < vcount && fe.from != fe.to
            ? net.edge(fe.from, fe.to)
            : -1;
    if (e < 0)
      throw InvalidInput(name + " joins vertices " + std::to_string(fe.from) + " and " +
                         std::to_string(fe.to) + ", which share no edge of the mesh; give an edge");
    if (fe.points.rows() != n + 1 || !fe.points.allFinite())
      throw InvalidInput(
          name + " has " + std::to_string(fe.points.rows()) +
          " points (or some not finite); give degree + 1 = " + std::to_string(n + 1));
    const std::vector<int> along = net.edge_points(e, fe.from);
    for (int s = 0; s <= n; ++s) {
      if (s == 0 || s == n) {
        const int v = along[s];
        if (placed_by[v] >= 0 && (start.row(v) - fe.points.row(s)).norm() > 1e-9 * size)
          throw InvalidInput(name + " and fixed edge " + std::to_string(placed_by[v]) +
                             " put vertex " + std::to_string(v) +
                             " at different places; give "
                             "curves that meet there");
        placed_by[v] = static_cast<int>(ei);
      }
      start.row(along[s]) = fe.points.row(s);
      prescribed[along[s]] = true;
    }
  }

  // Fixed points and the free numbering.
  std::vector<int> free_index(count, -1);
  std::vector<int> free_points;
  std::vector<bool> interpolated(vcount, problem.interpolate_vertices);
  for (int v : problem.free_vertices) {
    if (v < 0 || v >= vcount)
      throw InvalidInput("free vertex " + std::to_string(v) +
                         " is not a vertex of the mesh (0 to " + std::to_string(vcount - 1) +
                         "); give vertices of the mesh");
    interpolated[v] = false;
  }
  for (int k = 0; k < count; ++k)
    if (!prescribed[k] && !(k < vcount && interpolated[k])) {
      free_index[k] = static_cast<int>(free_points.size());
      free_points.push_back(k);
    }
  const int nf = static_cast<int>(free_points.size());
  report.unknowns = 3 * nf;
  if (nf == 0) {
    result.control = start;
  } else {
    // Column selections: free (nf) and fixed.
    Triplets pf_terms, px_terms;
    int fixed_count = 0;
    std::vector<int> fixed_points;
    for (int k = 0; k < count; ++k) {
      if (free_index[k] >= 0) {
        pf_terms.emplace_back(k, free_index[k], 1.0);
      } else {
        px_terms.emplace_back(k, fixed_count++, 1.0);
        fixed_points.push_back(k);
      }
    }
    Sparse pf(count, nf), px(count, fixed_count);
    pf.setFromTriplets(pf_terms.begin(), pf_terms.end());
    px.setFromTriplets(px_terms.begin(), px_terms.end());
    Eigen::MatrixX3d x_fixed(fixed_count, 3);
    for (int k = 0; k < fixed_count; ++k) x_fixed.row(k) = start.row(fixed_points[k]);

    // The user's constraints, each as rows over the 3 N coordinates.
    std::vector<Row> rows;
    std::vector<int> row_constraint;
    for (std::size_t ci = 0; ci < problem.constraints.size(); ++ci) {
      TriangularConstraint c = problem.constraints[ci];
      const std::string name = "constraint " + std::to_string(ci);
      if (c.triangle < 0 || c.triangle >= tcount)
        throw InvalidInput(name + " names triangle " + std::to_string(c.triangle) + " of " +
                           std::to_string(tcount));
      if (!c.at.allFinite() || !c.target.allFinite() || !c.direction.allFinite() ||
          c.at.minCoeff() < -1e-9 || std::abs(c.at.sum() - 1.0) > 1e-9)
        throw InvalidInput(name +
                           " lies outside its triangle (barycentric coordinates must be "
                           ">= 0 and sum to 1) or is not finite; place it on the triangle");
      if (c.kind != TriangularConstraint::Kind::point && !(c.direction.norm() > 0.0))
        throw InvalidInput(name + " has a zero direction; give a direction");
      if (std::binary_search(net.flipped.begin(), net.flipped.end(), c.triangle))
        std::swap(c.at(1), c.at(2));
      const std::vector<int>& control = net.control[c.triangle];
      const Eigen::Vector3d d = c.direction.normalized();
      const Eigen::VectorXd value = bernstein(n, c.at);
      const auto add = [&](Row r) {
        rows.push_back(std::move(r));
        row_constraint.push_back(static_cast<int>(ci));
      };
      switch (c.kind) {
        case TriangularConstraint::Kind::point:
          for (int a = 0; a < 3; ++a)
            add(row_of(control, value, Eigen::Vector3d::Unit(a), count, c.target(a)));
          break;
        case TriangularConstraint::Kind::normal:
          for (const Eigen::Vector3d& dir :
               {Eigen::Vector3d(-1.0, 1.0, 0.0), Eigen::Vector3d(-1.0, 0.0, 1.0)})
            add(row_of(control, bernstein_derivative(n, c.at, dir), d, count, 0.0));
          break;
        case TriangularConstraint::Kind::plane:
          add(row_of(control, value, d, count, d.dot(c.target)));
          break;
        case TriangularConstraint::Kind::line:
          for (const Eigen::Vector3d& axis : perpendiculars(d))
            add(row_of(control, value, axis, count, axis.dot(c.target)));
          break;
      }
    }
    report.constraint_rows = static_cast<int>(rows.size());

    // The operators: where each acts, its weight (strength made relative as a sheet's).
    std::vector<int> every(tcount);
    std::iota(every.begin(), every.end(), 0);
    const OperatorScales scales =
        operator_scales(triangles_domain(net, every, problem.equilateral_domain), q);
    struct Prepared {
      const TriangularOperator* op;
      OperatorDomain domain;
      Eigen::Vector3d direction;
      double weight;
    };
    using Kind = TriangularOperator::Kind;
    std::vector<Prepared> operators;
    bool nonlinear = false;
    for (std::size_t oi = 0; oi < problem.operators.size(); ++oi) {
      const TriangularOperator& op = problem.operators[oi];
      const std::string name = "operator " + std::to_string(oi);
      if (!(std::isfinite(op.strength) && op.strength >= 0.0))
        throw InvalidInput(name + " has a strength that is negative or not finite; give one >= 0");
      if (!op.origin.allFinite() || !op.direction.allFinite())
        throw InvalidInput(name + " has a point or direction that is not finite; give finite ones");
      for (const int t : op.triangles)
        if (t < 0 || t >= tcount)
          throw InvalidInput(name + " names triangle " + std::to_string(t) + " of " +
                             std::to_string(tcount) + "; give triangles of the mesh");
      const bool directed = op.kind == Kind::plane_attractor || op.kind == Kind::line_attractor ||
                            op.kind == Kind::director;
      if (directed && !(op.direction.norm() > 0.0))
        throw InvalidInput(name + " has a zero direction; give a direction");
      if (op.kind == Kind::shape_attractor && !op.closest)
        throw InvalidInput(name + " attracts to no shape; give its target");
      if (op.strength == 0.0) continue;
      nonlinear |= op.kind == Kind::repeller || op.kind == Kind::shape_attractor;
      operators.push_back(
          {&op,
           triangles_domain(net, op.triangles.empty() ? every : op.triangles,
                            problem.equilateral_domain),
           directed ? Eigen::Vector3d(op.direction.normalized()) : Eigen::Vector3d::UnitZ(),
           op.strength * (op.kind == Kind::director ? scales.gradient : scales.value)});
    }
    report.assembly_seconds = seconds_since(t0);

    // Exact user constraints through the factored energy: d = d0 - Y lambda, Y = K^-1 H^T,
    // (H Y) lambda = H d0 - h, least squares where the constraints conflict.
    const int m = static_cast<int>(rows.size());
    Sparse hm(m, 3 * nf);
    Eigen::VectorXd h(m);
    if (m > 0) {
      Triplets h_terms;
      for (int r = 0; r < m; ++r) {
        h(r) = rows[r].rhs;
        for (const auto& [column, value] : rows[r].terms) {
          const int point = column % count, axis = column / count;
          h(r) -= value * start(point, axis);
          if (free_index[point] >= 0) h_terms.emplace_back(r, axis * nf + free_index[point], value);
        }
      }
      hm.setFromTriplets(h_terms.begin(), h_terms.end());
    }
    const Sparse f_f = f * pf;
    const Eigen::MatrixX3d start_free = pf.transpose() * start;
    const Eigen::MatrixX3d start_g1 = f * start;  // rows x 3
    Eigen::MatrixX3d current = start;
    const int iterations = nonlinear ? std::max(1, problem.nonlinear_iterations) : 1;
    for (int iteration = 0; iteration < iterations; ++iteration) {
      QuadraticTerms terms(count);
      for (const Prepared& p : operators) {
        const TriangularOperator& op = *p.op;
        switch (op.kind) {
          case Kind::point_attractor:
            attractor_terms(p.domain, AttractorKind::point, op.origin, p.direction, p.weight,
                            terms);
            break;
          case Kind::plane_attractor:
            attractor_terms(p.domain, AttractorKind::plane, op.origin, p.direction, p.weight,
                            terms);
            break;
          case Kind::line_attractor:
            attractor_terms(p.domain, AttractorKind::line, op.origin, p.direction, p.weight, terms);
            break;
          case Kind::director:
            director_terms(p.domain, p.direction, p.weight, terms);
            break;
          case Kind::repeller:
            repeller_terms(p.domain, op.origin, p.weight, current, 1e-6 * size, terms);
            break;
          case Kind::shape_attractor:
            shape_attractor_terms(p.domain, op.closest, p.weight, current, terms);
            break;
        }
      }
      Sparse separable(count, count);
      separable.setFromTriplets(terms.separable.begin(), terms.separable.end());
      const Sparse q_all = q + separable;
      const Sparse q_ff = pf.transpose() * q_all * pf;
      double weight = 0.0;
      if (f_rows > 0) {
        const double q_scale = q_ff.diagonal().sum() / nf;
        const double f_scale = f_f.squaredNorm() / nf;
        if (f_scale > 0.0) weight = problem.g1_weight * q_scale / f_scale;
      }
      Sparse k = q_ff;
      if (weight > 0.0) k += weight * Sparse(f_f.transpose() * f_f);
      k.makeCompressed();
      // The energy of the points, or of their displacement from the flat start (whose fixed
      // points do not move, so only the free ones' part remains).
      Eigen::MatrixX3d rhs = (problem.energy_of_displacement
                                  ? Eigen::MatrixX3d(pf.transpose() * (q * start))
                                  : Eigen::MatrixX3d(-(pf.transpose() * (q * (px * x_fixed))))) -
                             pf.transpose() * (separable * (px * x_fixed)) +
                             pf.transpose() * terms.separable_f;
      if (weight > 0.0) rhs -= weight * (f_f.transpose() * (f * (px * x_fixed)));

      Factor factor;
      factor.nf = nf;
      factor.flat = terms.uses_coupled();
      factor.use_cg = problem.solver == TriangularSolver::cg ||
                      (problem.solver == TriangularSolver::automatic && 3 * nf > problem.cg_above);
      if (factor.use_cg) {
        factor.cg.setTolerance(problem.cg_tolerance);
        factor.cg.setMaxIterations(problem.cg_iterations);
      }
      report.solver = factor.use_cg ? "cg" : "direct";
      Sparse system = k;
      if (factor.flat) {
        // The energy once per coordinate and the coupling terms (3 p + c in the terms,
        // c nf + free index here; fixed points move to the right-hand side).
        Triplets big;
        for (int a = 0; a < 3; ++a)
          for (int col = 0; col < k.outerSize(); ++col)
            for (Sparse::InnerIterator it(k, col); it; ++it)
              big.emplace_back(a * nf + static_cast<int>(it.row()), a * nf + col, it.value());
        for (const auto& term : terms.coupled) {
          const int p = term.row() / 3, c = term.row() % 3, o = term.col() / 3, e = term.col() % 3;
          if (free_index[p] < 0) continue;
          if (free_index[o] >= 0)
            big.emplace_back(c * nf + free_index[p], e * nf + free_index[o], term.value());
          else
            rhs(free_index[p], c) -= term.value() * start(o, e);
        }
        for (int p = 0; p < count; ++p)
          if (free_index[p] >= 0)
            for (int c = 0; c < 3; ++c) rhs(free_index[p], c) += terms.coupled_f(3 * p + c);
        system.resize(3 * nf, 3 * nf);
        system.setFromTriplets(big.begin(), big.end());
      }
      factor.compute(system);
      const auto times = [&](const Eigen::MatrixX3d& v) -> Eigen::MatrixX3d {
        if (!factor.flat) return k * v;
        const Eigen::VectorXd out = system * Eigen::Map<const Eigen::VectorXd>(v.data(), 3 * nf);
        return Eigen::Map<const Eigen::MatrixX3d>(out.data(), nf, 3);
      };
      // Solved for the displacement from the flat start, so that a start nothing moves (a planar
      // mesh) comes back to rounding instead of through K^-1 (K start).
      const Eigen::MatrixX3d base = rhs - times(start_free);
      Eigen::MatrixXd y;
      Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
      if (m > 0) {
        y = factor.coordinates(Eigen::MatrixXd(hm.transpose()));
        cod.setThreshold(1e-10);
        cod.compute(hm * y);
      }
      const auto solve = [&](const Eigen::MatrixX3d& b) {
        Eigen::MatrixX3d d = factor.points(b);
        if (m == 0) return d;
        Eigen::Map<Eigen::VectorXd> flat(d.data(), 3 * nf);
        flat -= y * cod.solve(hm * flat - h);
        return d;
      };
      Eigen::MatrixX3d x = solve(base);
      // The G1 rows by the method of multipliers: each round moves the multipliers by the weight
      // times the rows' residual and solves again with the same factor, so rows that can be met
      // are met to rounding without a weight that would ruin the factor's accuracy; rows that
      // conflict stop shrinking, and the rounds stop there.
      report.g1_rounds = 0;
      if (weight > 0.0) {
        Eigen::MatrixX3d multipliers = Eigen::MatrixX3d::Zero(f_rows, 3);
        double last = (f_f * x + start_g1).cwiseAbs().maxCoeff();
        for (int round = 0; round < problem.g1_rounds && last > 0.0; ++round) {
          multipliers += weight * (f_f * x + start_g1);
          const Eigen::MatrixX3d next = solve(base - f_f.transpose() * multipliers);
          const double now = (f_f * next + start_g1).cwiseAbs().maxCoeff();
          x = next;
          ++report.g1_rounds;
          if (now > 0.9 * last) break;  // stalled: the rows left conflict
          last = now;
        }
      }
      x += start_free;
      report.cg_iterations = std::max(report.cg_iterations, factor.iterations);
      report.cg_error = std::max(report.cg_error, factor.error);
      Eigen::MatrixX3d next = start;
      for (int i = 0; i < nf; ++i) next.row(free_points[i]) = x.row(i);
      if (!next.allFinite())
        throw SolveFailure("the triangular surface's solve gave points that are not finite");
      const double moved = (next - current).cwiseAbs().maxCoeff();
      current = next;
      if (nonlinear) report.operator_iterations = iteration + 1;
      if (!nonlinear || moved <= problem.nonlinear_tolerance * size) break;
    }
    result.control = current;
    report.solve_seconds = seconds_since(t0) - report.assembly_seconds;
  }

  result.patches.resize(tcount);
  for (int t = 0; t < tcount; ++t) {
    result.patches[t].degree = n;
    result.patches[t].points.resize(triangle_points(n), 3);
    for (int l = 0; l < triangle_points(n); ++l)
      result.patches[t].points.row(l) = result.control.row(net.control[t][l]);
  }
  const double before_measure = seconds_since(t0);
  const std::vector<double> angles = edge_angles(net, result.patches, problem.angle_samples);
  report.edges_measured = static_cast<int>(angles.size());
  int inner = 0;
  for (const NetEdge& e : net.edges) {
    if (e.right < 0) continue;
    const double angle = angles[inner++];
    report.worst_angle = std::max(report.worst_angle, angle);
    if (problem.g1 && angle > problem.angle_tolerance) {
      report.overruled_edges.push_back({e.a, e.b});
      report.overruled_angles.push_back(angle);
    }
  }
  report.shortest_tangent = 1.0;
  for (int ei = 0; ei < static_cast<int>(net.edges.size()); ++ei) {
    const std::vector<int> along = net.edge_points(ei, net.edges[ei].a);
    const double length = (result.control.row(along[n]) - result.control.row(along[0])).norm();
    for (const int end : {0, n}) {
      const int next = end == 0 ? 1 : n - 1;
      const double ratio =
          length > 0.0
              ? (result.control.row(along[next]) - result.control.row(along[end])).norm() / length
              : 0.0;
      report.shortest_tangent = std::min(report.shortest_tangent, ratio);
      if (ratio < 0.01) report.singular_vertices.push_back(along[end]);
    }
  }
  std::sort(report.singular_vertices.begin(), report.singular_vertices.end());
  report.singular_vertices.erase(
      std::unique(report.singular_vertices.begin(), report.singular_vertices.end()),
      report.singular_vertices.end());
  // The user's constraints as the surface now meets them, measured on the patches.
  for (const TriangularConstraint& given : problem.constraints) {
    TriangularConstraint c = given;
    if (std::binary_search(net.flipped.begin(), net.flipped.end(), c.triangle))
      std::swap(c.at(1), c.at(2));
    const TriangularBezier& patch = result.patches[c.triangle];
    const Eigen::Vector3d p = patch.evaluate(c.at);
    const Eigen::Vector3d d = c.direction.normalized();
    double r = 0.0;
    switch (c.kind) {
      case TriangularConstraint::Kind::point:
        r = (p - c.target).norm();
        break;
      case TriangularConstraint::Kind::normal:
        r = patch_normal(patch, c.at).cross(d).norm();
        break;
      case TriangularConstraint::Kind::plane:
        r = std::abs((p - c.target).dot(d));
        break;
      case TriangularConstraint::Kind::line:
        r = (p - c.target).cross(d).norm();
        break;
    }
    report.constraint_residual = std::max(report.constraint_residual, r);
  }
  report.measure_seconds = seconds_since(t0) - before_measure;
  return result;
}

}  // namespace varsurf
