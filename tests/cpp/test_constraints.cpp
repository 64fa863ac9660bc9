// SPDX-License-Identifier: LGPL-2.1-or-later
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "test_support.hpp"
#include "varsurf/core/constraints.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/gauss_legendre.hpp"
#include "varsurf/core/sheet_solver.hpp"

using namespace varsurf;

namespace {

// A curved reference surface of the given space, and its exact image of the iso line u = u0.
Eigen::MatrixX3d reference_poles(const SplineSpace& sp) {
  return test::fit_poles(sp, [](double u, double v) {
    return Eigen::Vector3d(10 * u, 8 * v + u * u, std::sin(3 * u) * std::cos(2 * v));
  });
}

CurveConstraint iso_u(const SplineSpace& sp, const Eigen::MatrixX3d& poles, double u0) {
  CurveConstraint c;
  c.preimage = test::line_curve(Eigen::Vector2d(u0, 0.0), Eigen::Vector2d(u0, 1.0));
  c.target = test::fit_piecewise_curve(
      breakpoints(sp.knots_v, sp.degree_v), sp.degree_v, 3, [&](double t) {
        return Eigen::VectorXd(evaluate_surface(sp, poles, u0, t, 0).row(0).transpose());
      });
  return c;
}

CurveConstraint iso_v(const SplineSpace& sp, const Eigen::MatrixX3d& poles, double v0) {
  CurveConstraint c;
  c.preimage = test::line_curve(Eigen::Vector2d(0.0, v0), Eigen::Vector2d(1.0, v0));
  c.target = test::fit_piecewise_curve(
      breakpoints(sp.knots_u, sp.degree_u), sp.degree_u, 3, [&](double t) {
        return Eigen::VectorXd(evaluate_surface(sp, poles, t, v0, 0).row(0).transpose());
      });
  return c;
}

SheetProblem bare_problem(const SplineSpace& sp) {
  SheetProblem pb;
  pb.space = sp;
  pb.initial_poles = Eigen::MatrixX3d::Zero(sp.size(), 3);
  pb.energy = ThinPlateWeights::isotropic(0.1, 1.0);
  return pb;
}

}  // namespace

TEST(CurveConstraint, IsoLineHasOneIndependentRowPerPole) {
  // w(u0, v) = sum_j (sum_i N_i(u0) P_ij) N_j(v): an iso line fixes nv combinations of poles.
  const SplineSpace sp = SplineSpace::uniform(3, 3, 5, 4);
  const Eigen::MatrixX3d ref = reference_poles(sp);
  SheetProblem pb = bare_problem(sp);
  pb.curves.push_back(iso_u(sp, ref, 0.37));
  const SolveResult r = solve_sheet(pb);
  EXPECT_EQ(r.report.constraint_rank, sp.nv());
  EXPECT_GT(r.report.constraint_samples, sp.nv());
  EXPECT_LT(incidence_error(sp, r.poles, pb.curves[0]), 1e-10);
}

TEST(CurveConstraint, CrossingCurvesShareOneRow) {
  // Two crossing iso lines constrain nu + nv - 1 combinations: the crossing point is shared, and
  // its duplicate row must be reduced away for the KKT system to stay solvable.
  const SplineSpace sp = SplineSpace::uniform(3, 3, 4, 6);
  const Eigen::MatrixX3d ref = reference_poles(sp);
  SheetProblem pb = bare_problem(sp);
  pb.curves.push_back(iso_u(sp, ref, 0.41));
  pb.curves.push_back(iso_v(sp, ref, 0.63));
  const SolveResult r = solve_sheet(pb);
  EXPECT_EQ(r.report.constraint_rank, sp.nu() + sp.nv() - 1);
  EXPECT_EQ(r.report.clusters, 1);
  EXPECT_LT(incidence_error(sp, r.poles, pb.curves[0]), 1e-10);
  EXPECT_LT(incidence_error(sp, r.poles, pb.curves[1]), 1e-10);
}

TEST(CurveConstraint, PointOnCurveAddsNoRow) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 5, 4);
  const Eigen::MatrixX3d ref = reference_poles(sp);
  SheetProblem pb = bare_problem(sp);
  pb.curves.push_back(iso_u(sp, ref, 0.37));
  PointConstraint p;
  p.u = 0.37;
  p.v = 0.52;
  p.target = evaluate_surface(sp, ref, p.u, p.v, 0).row(0).transpose();
  pb.points.push_back(p);
  const SolveResult r = solve_sheet(pb);
  EXPECT_EQ(r.report.constraint_rank, sp.nv());
  EXPECT_LT((evaluate_surface(sp, r.poles, p.u, p.v, 0).row(0).transpose() - p.target).norm(),
            1e-10);
}

TEST(CurveConstraint, DisjointCurvesFormSeparateClusters) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 8, 8);
  const Eigen::MatrixX3d ref = reference_poles(sp);
  SheetProblem pb = bare_problem(sp);
  pb.curves.push_back(iso_u(sp, ref, 0.1));
  pb.curves.push_back(iso_u(sp, ref, 0.9));
  const SolveResult r = solve_sheet(pb);
  EXPECT_EQ(r.report.clusters, 2);
  EXPECT_EQ(r.report.constraint_rank, 2 * sp.nv());
}

TEST(CurveConstraint, WeightsSumToTheCurveWeight) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 4, 4);
  CurveConstraint c = iso_u(sp, reference_poles(sp), 0.3);
  c.weight = 2.5;
  const ConstraintSamples s = sample_curve(sp, c);
  double total = 0.0;
  for (const Eigen::VectorXd& row : s.coeff) total += row.sum() * row.sum();  // (sqrt(w) * 1)^2
  EXPECT_NEAR(total, 2.5, 1e-12);
}

TEST(CurveConstraint, RejectsBadCurves) {
  const SplineSpace sp = SplineSpace::uniform(3, 3, 4, 4);
  CurveConstraint c;
  c.target = test::line_curve(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0));
  c.preimage =
      test::line_curve(Eigen::Vector2d(0.2, 0.2), Eigen::Vector2d(1.3, 0.2));  // leaves domain
  EXPECT_THROW(sample_curve(sp, c), InvalidInput);
  c.preimage = test::line_curve(Eigen::Vector2d(0.2, 0.2), Eigen::Vector2d(0.8, 0.2), 0.0, 2.0);
  EXPECT_THROW(sample_curve(sp, c), InvalidInput);  // parameter ranges differ
  c.preimage = test::line_curve(Eigen::Vector2d(0.2, 0.2), Eigen::Vector2d(0.8, 0.2));
  c.target = test::line_curve(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(1, 1, 1));
  EXPECT_THROW(sample_curve(sp, c), InvalidInput);  // zero length
  c.target = test::line_curve(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, NAN));
  EXPECT_THROW(sample_curve(sp, c), InvalidInput);
  c.target = test::line_curve(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0));
  EXPECT_THROW(sample_curve(sp, c), InvalidInput);  // target must be 3D
  PointConstraint p;
  p.u = NAN;
  EXPECT_THROW(sample_point(sp, p), InvalidInput);
}

// An exact straight pre-image (a line seen over a flat sheet) lands on the knot lines exactly at
// evenly spaced samples: each crossing still splits the quadrature, so that every piece is one
// polynomial (the diagonal crosses the 8-span lines at u = v = 3/8, 1/2, 5/8: four pieces), each
// with a straight pre-image's count of points.
// The Gram matrix sum_k w_k b(c(t_k)) b(c(t_k))^T of a curve's samples against a fine composite
// Gauss rule (2 000 pieces of 4 points: its own error is below 1e-12 here).
Eigen::MatrixXd gram(const SplineSpace& space, const CurveConstraint& c, const CurveSampling& s) {
  const ConstraintSamples rows = sample_curve(space, c, s);
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(space.size(), space.size());
  for (size_t r = 0; r < rows.index.size(); ++r)
    for (size_t i = 0; i < rows.index[r].size(); ++i)
      for (size_t j = 0; j < rows.index[r].size(); ++j)
        g(rows.index[r][i], rows.index[r][j]) += rows.coeff[r](static_cast<Eigen::Index>(i)) *
                                                 rows.coeff[r](static_cast<Eigen::Index>(j));
  return g;
}

CurveSampling fine_sampling(double t0, double t1) {
  const GaussRule& rule = gauss_legendre(4);
  CurveSampling s;
  const int pieces = 2000;
  for (int i = 0; i < pieces; ++i) {
    const double a = t0 + (t1 - t0) * i / pieces, h = 0.5 * (t1 - t0) / pieces;
    for (size_t q = 0; q < rule.nodes.size(); ++q) {
      s.t.push_back(a + h * (rule.nodes[q] + 1.0));
      s.rule_weight.push_back(rule.weights[q] * h);
    }
  }
  return s;
}

// A pre-image of 40 cubic spans along a straight line, parametrized unevenly (as a projected
// edge is), leaves each piece's chord by about 1e-4 of a knot span: its pieces take a straight
// pre-image's 7 points instead of 19, and the samples' Gram matrix stays that of the exact
// integral (measured: 7e-15 relative). A quarter circle of as many spans bends more: its pieces
// beyond 1e-3 of a span keep the exact count (its Gram: 1e-13).
TEST(CurveConstraint, NearlyStraightPiecesTakeFewerSamplesAndKeepTheGram) {
  const SplineSpace space = SplineSpace::uniform(3, 3, 8, 8);
  std::vector<double> breaks;
  for (int i = 0; i <= 40; ++i) breaks.push_back(i / 40.0);
  const auto uneven = [](double t) { return t + 0.05 * std::sin(M_PI * t); };
  CurveConstraint straight;
  straight.preimage = test::fit_piecewise_curve(breaks, 3, 2, [&](double t) {
    return Eigen::VectorXd(Eigen::Vector2d(0.2, 0.3) + uneven(t) * Eigen::Vector2d(0.6, 0.5));
  });
  straight.target = test::fit_piecewise_curve(breaks, 3, 3, [&](double t) {
    return Eigen::VectorXd(Eigen::Vector3d(20, 30, 5) + uneven(t) * Eigen::Vector3d(60, 50, 8));
  });
  const CurveSampling s = curve_sampling(space, straight);
  EXPECT_LT(s.t.size(), static_cast<size_t>(50 * 7));  // 40 spans and a few knot crossings
  const Eigen::MatrixXd exact = gram(space, straight, fine_sampling(0.0, 1.0));
  EXPECT_LT((gram(space, straight, s) - exact).cwiseAbs().maxCoeff(),
            1e-10 * exact.cwiseAbs().maxCoeff());

  CurveConstraint arc;
  arc.preimage = test::fit_piecewise_curve(breaks, 3, 2, [](double t) {
    const double a = 0.5 * M_PI * t;
    return Eigen::VectorXd(Eigen::Vector2d(0.1 + 0.8 * std::cos(a), 0.1 + 0.8 * std::sin(a)));
  });
  arc.target = test::fit_piecewise_curve(breaks, 3, 3, [](double t) {
    const double a = 0.5 * M_PI * t;
    return Eigen::VectorXd(Eigen::Vector3d(10 + 80 * std::cos(a), 10 + 80 * std::sin(a), 3));
  });
  const CurveSampling bent = curve_sampling(space, arc);
  const Eigen::MatrixXd arc_exact = gram(space, arc, fine_sampling(0.0, 1.0));
  EXPECT_GT(bent.t.size(), s.t.size() + 40);
  EXPECT_LT((gram(space, arc, bent) - arc_exact).cwiseAbs().maxCoeff(),
            1e-10 * arc_exact.cwiseAbs().maxCoeff());
}

TEST(CurveConstraint, ExactKnotLineHitsSplitTheQuadrature) {
  const SplineSpace space = SplineSpace::uniform(3, 3, 8, 8);
  Eigen::VectorXd a(2), b(2), p(3), q(3);
  a << 0.25, 0.25;
  b << 0.75, 0.75;
  p << 25.0, 25.0, 14.0;
  q << 75.0, 75.0, 14.0;
  BSplineCurve pre = test::line_curve(a, b);
  // The same line as one cubic Bezier segment (the degree the solver's sampling expects).
  pre.degree = 3;
  pre.knots = {0, 0, 0, 0, 1, 1, 1, 1};
  pre.poles.resize(4, 2);
  for (int i = 0; i < 4; ++i) pre.poles.row(i) = (a + (b - a) * (i / 3.0)).transpose();
  const CurveConstraint c{pre, test::line_curve(p, q), 1.0};
  const CurveSampling s = curve_sampling(space, c);
  const int per_piece = 3 + 3 + 1;
  ASSERT_EQ(s.t.size(), static_cast<size_t>(4 * per_piece));
  for (double cut : {0.25, 0.5, 0.75}) {  // no sample straddles a crossing
    const auto after = std::upper_bound(s.t.begin(), s.t.end(), cut);
    EXPECT_NE(after, s.t.begin());
    EXPECT_EQ((after - s.t.begin()) % per_piece, 0) << cut;
  }
}
