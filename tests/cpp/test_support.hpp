// SPDX-License-Identifier: LGPL-2.1-or-later
// Helpers shared by the core tests: exact pole fits of representable functions, Greville points.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/knot_vector.hpp"
#include "varsurf/core/sheet_solver.hpp"
#include "varsurf/core/spline_space.hpp"

namespace varsurf::test {

using varsurf::greville;

// Poles of the surface interpolating f at the Greville grid: exact when f lies in the space.
inline Eigen::MatrixX3d fit_poles(const SplineSpace& space,
                                  const std::function<Eigen::Vector3d(double, double)>& f) {
  const std::vector<double> gu = greville(space.knots_u, space.degree_u);
  const std::vector<double> gv = greville(space.knots_v, space.degree_v);
  const int n = space.size();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixX3d b(n, 3);
  for (int i = 0; i < space.nu(); ++i)
    for (int j = 0; j < space.nv(); ++j) {
      const int row = space.index(i, j);
      const BasisSample s = space.basis(gu[static_cast<size_t>(i)], gv[static_cast<size_t>(j)], 0);
      for (size_t k = 0; k < s.index.size(); ++k)
        a(row, s.index[k]) = s.values(0, static_cast<Eigen::Index>(k));
      b.row(row) = f(gu[static_cast<size_t>(i)], gv[static_cast<size_t>(j)]).transpose();
    }
  return a.fullPivLu().solve(b);
}

// Piecewise Bezier curve (C0, interior knots of multiplicity `degree`) through f on each piece:
// exact when f restricted to every piece is a polynomial of degree <= `degree`.
inline BSplineCurve fit_piecewise_curve(const std::vector<double>& breaks, int degree, int dim,
                                        const std::function<Eigen::VectorXd(double)>& f) {
  BSplineCurve c;
  c.degree = degree;
  const int pieces = static_cast<int>(breaks.size()) - 1;
  c.knots.assign(static_cast<size_t>(degree + 1), breaks.front());
  for (int k = 1; k < pieces; ++k)
    c.knots.insert(c.knots.end(), static_cast<size_t>(degree), breaks[static_cast<size_t>(k)]);
  c.knots.insert(c.knots.end(), static_cast<size_t>(degree + 1), breaks.back());
  const int n = static_cast<int>(c.knots.size()) - degree - 1;
  // Collocation at Chebyshev points of each piece plus the shared ends: n conditions.
  std::vector<double> ts;
  for (int k = 0; k < pieces; ++k) {
    const double a = breaks[static_cast<size_t>(k)], b = breaks[static_cast<size_t>(k + 1)];
    for (int i = (k == 0 ? 0 : 1); i <= degree; ++i)
      ts.push_back(a + (b - a) * 0.5 * (1.0 - std::cos(M_PI * i / degree)));
  }
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd rhs(n, dim);
  for (int r = 0; r < n; ++r) {
    const double t = ts[static_cast<size_t>(r)];
    const int span = find_span(c.knots, degree, t);
    Eigen::MatrixXd nd(1, degree + 1);
    basis_derivatives(c.knots, degree, span, t, 0, nd);
    for (int j = 0; j <= degree; ++j) a(r, span - degree + j) = nd(0, j);
    rhs.row(r) = f(t).transpose();
  }
  c.poles = a.fullPivLu().solve(rhs);
  return c;
}

// The unit square as poles of the space: the flat sheet (u, v, 0).
// Options asking for one solve mode.
inline SolveOptions with_mode(SolveMode mode) {
  SolveOptions o;
  o.mode = mode;
  return o;
}

inline Eigen::MatrixX3d flat_poles(const SplineSpace& space) {
  return fit_poles(space, [](double u, double v) { return Eigen::Vector3d(u, v, 0.0); });
}

inline BSplineCurve line_curve(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double t0 = 0.0,
                               double t1 = 1.0) {
  BSplineCurve c;
  c.degree = 1;
  c.knots = {t0, t0, t1, t1};
  c.poles.resize(2, a.size());
  c.poles.row(0) = a.transpose();
  c.poles.row(1) = b.transpose();
  return c;
}

// Half a unit cylinder, two exact rational quarter circles along u (degree 2, weights 1, 1/sqrt 2,
// 1, ...) and z = 2 v along v (cubic, `spans_v` spans): a rational base like a Part cylinder's
// face.
inline SplineSpace half_cylinder_space(int spans_v = 3) {
  SplineSpace s;
  s.degree_u = 2;
  s.knots_u = {0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0};
  s.degree_v = 3;
  s.knots_v = uniform_clamped_knots(3, spans_v);
  const double h = std::sqrt(0.5);
  const double wu[5] = {1.0, h, 1.0, h, 1.0};
  s.weights.resize(s.size());
  for (int i = 0; i < s.nu(); ++i)
    for (int j = 0; j < s.nv(); ++j) s.weights(s.index(i, j)) = wu[i];
  return s;
}

inline Eigen::MatrixX3d half_cylinder_poles(const SplineSpace& s) {
  const double xy[5][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}};
  const std::vector<double> gv = greville(s.knots_v, s.degree_v);
  Eigen::MatrixX3d p(s.size(), 3);
  for (int i = 0; i < s.nu(); ++i)
    for (int j = 0; j < s.nv(); ++j)
      p.row(s.index(i, j)) << xy[i][0], xy[i][1], 2.0 * gv[static_cast<size_t>(j)];
  return p;
}

// Largest distance from a curve's samples (samples + 1 of them, evenly in its parameter) to the
// sheet at the same pre-image points.
inline double curve_gap(const SheetProblem& pb, const Eigen::MatrixX3d& poles,
                        const CurveConstraint& c, int samples = 200) {
  double gap = 0.0;
  for (int i = 0; i <= samples; ++i) {
    const double t = static_cast<double>(i) / samples;
    const Eigen::VectorXd uv = c.preimage.derivatives(t, 0).row(0).transpose();
    const Eigen::VectorXd p = c.target.derivatives(t, 0).row(0).transpose();
    gap =
        std::max(gap, (evaluate_surface(pb.space, poles, uv(0), uv(1), 0).transpose() - p).norm());
  }
  return gap;
}

// A free sheet over the unit square through its four sides, three wavy slanted curves and two
// pins, fitted to 1e-4 (a fit one refinement step reaches).
inline SheetProblem penalty_scene(int spans) {
  SheetProblem pb;
  pb.space = SplineSpace::uniform(3, 3, spans, spans);
  pb.initial_poles = flat_poles(pb.space);
  std::vector<double> breaks;
  for (int i = 0; i <= 12; ++i) breaks.push_back(i / 12.0);
  const double pi = std::acos(-1.0);
  const auto add = [&](Eigen::Vector2d a, Eigen::Vector2d b, double height, double wave,
                       int phase) {
    CurveConstraint c;
    c.preimage = line_curve(a, b);
    c.target = fit_piecewise_curve(breaks, 3, 3, [&](double t) {
      const Eigen::Vector2d uv = a + t * (b - a);
      return Eigen::VectorXd(
          Eigen::Vector3d(uv(0), uv(1), height + wave * std::sin(2.0 * pi * t + phase)));
    });
    pb.curves.push_back(c);
  };
  add({0, 0}, {1, 0}, 0.0, 0.02, 0);
  add({1, 0}, {1, 1}, 0.0, 0.02, 0);
  add({1, 1}, {0, 1}, 0.0, 0.02, 0);
  add({0, 1}, {0, 0}, 0.0, 0.02, 0);
  for (int j = 0; j < 3; ++j) add({0.2 + 0.25 * j, 0.15}, {0.3 + 0.25 * j, 0.85}, 0.05, 0.01, j);
  PointConstraint p;
  p.u = 0.35;
  p.v = 0.5;
  p.target = Eigen::Vector3d(0.35, 0.5, 0.06);
  pb.points.push_back(p);
  p.u = 0.6;
  p.v = 0.3;
  p.target = Eigen::Vector3d(0.6, 0.3, 0.04);
  pb.points.push_back(p);
  return pb;
}

}  // namespace varsurf::test
