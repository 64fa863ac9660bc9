// SPDX-License-Identifier: LGPL-2.1-or-later
// Local against uniform refinement (Welch & Witkin sec. 4.4): a flat bicubic sheet with its
// boundary kept and one interior wavy curve across it. Prints, as JSON lines, for each tolerance
// the hierarchical degrees of freedom that meet it and the poles of the uniform refinement
// (spans doubled from one) that meets it, with both times.
#include <Eigen/LU>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "varsurf/core/hierarchical_solver.hpp"
#include "varsurf/core/knot_vector.hpp"

using namespace varsurf;

namespace {

constexpr double pi = 3.14159265358979323846;

Eigen::MatrixX3d flat(const SplineSpace& s) {
  // Greville abscissae give the identity map (u, v, 0).
  const auto grev = [](const std::vector<double>& k, int p, int i) {
    double g = 0.0;
    for (int j = 1; j <= p; ++j) g += k[static_cast<size_t>(i + j)];
    return g / p;
  };
  Eigen::MatrixX3d poles(s.size(), 3);
  for (int i = 0; i < s.nu(); ++i)
    for (int j = 0; j < s.nv(); ++j)
      poles.row(s.index(i, j)) << grev(s.knots_u, s.degree_u, i), grev(s.knots_v, s.degree_v, j),
          0.0;
  return poles;
}

SheetProblem problem(int spans) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, spans, spans);
  pb.initial_poles = flat(pb.space);
  pb.energy = ThinPlateWeights::isotropic(0.0, 1.0);
  pb.fixed_poles = boundary_pole_indices(pb.space);
  CurveConstraint c;
  c.preimage.degree = 1;
  c.preimage.knots = {0, 0, 1, 1};
  c.preimage.poles.resize(2, 2);
  c.preimage.poles << 0.15, 0.2, 0.85, 0.75;
  // The target: a wave of six periods, interpolated by 64 cubic pieces at their Greville points.
  const int n = 67;
  c.target.degree = 3;
  c.target.knots = uniform_clamped_knots(3, 64);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n), b(n, 3);
  for (int r = 0; r < n; ++r) {
    double t = 0.0;
    for (int j = 1; j <= 3; ++j) t += c.target.knots[static_cast<size_t>(r + j)];
    t /= 3.0;
    const int span = find_span(c.target.knots, 3, t);
    Eigen::MatrixXd nd(1, 4);
    basis_derivatives(c.target.knots, 3, span, t, 0, nd);
    for (int j = 0; j <= 3; ++j) a(r, span - 3 + j) = nd(0, j);
    b.row(r) << 0.15 + 0.7 * t, 0.2 + 0.55 * t, 0.02 * std::sin(12 * pi * t) * std::sin(pi * t);
  }
  c.target.poles = a.fullPivLu().solve(b);
  pb.curves.push_back(c);
  return pb;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

int main() {
  SolveOptions opt;  // automatic mode
  for (double tol : {1e-4, 1e-5, 1e-6}) {
    HierarchicalOptions ho;
    ho.tolerance = tol;
    ho.max_depth = 8;
    auto t = std::chrono::steady_clock::now();
    const HierarchicalResult h = solve_hierarchical(problem(1), ho, opt);
    const double th = seconds_since(t);
    int uniform = 0, spans = 1;
    t = std::chrono::steady_clock::now();
    for (; spans <= 256 && uniform == 0; spans *= 2) {
      const SheetProblem u = problem(spans);
      const SolveResult s = solve_sheet(u, opt);
      if (incidence_error(u.space, s.poles, u.curves[0], ho.samples) <= tol)
        uniform = u.space.size();
    }
    const double tu = seconds_since(t);
    std::printf(
        "{\"tolerance\": %g, \"met\": %s, \"depth\": %d, \"dofs\": %d, \"export_poles\": %d, "
        "\"hier_seconds\": %.3f, \"uniform_poles\": %d, \"uniform_seconds\": %.3f}\n",
        tol, h.report.met ? "true" : "false", h.report.depth, h.report.dofs, h.report.export_poles,
        th, uniform, tu);
  }
  return 0;
}
