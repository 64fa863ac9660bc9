// SPDX-License-Identifier: LGPL-2.1-or-later
// Locally refined spline spaces (Welch & Witkin sec. 3): knot insertion as a linear map, layers,
// their degrees of freedom, and the exact export to one tensor-product B-spline.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <random>

#include "test_support.hpp"
#include "varsurf/core/bspline_curve.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/hierarchical_space.hpp"
#include "varsurf/core/knot_refinement.hpp"
#include "varsurf/core/knot_vector.hpp"

using namespace varsurf;

TEST(KnotRefinement, TheRefinedCurveIsTheSameCurve) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> r(-1.0, 1.0);
  for (int degree : {2, 3, 5}) {
    BSplineCurve c;
    c.degree = degree;
    c.knots = flat_knots({0.0, 0.3, 0.5, 1.0}, {degree + 1, 1, 2, degree + 1});
    c.poles = Eigen::MatrixXd::NullaryExpr(static_cast<Eigen::Index>(c.knots.size()) - degree - 1,
                                           3, [&] { return r(rng); });
    BSplineCurve f = c;
    f.knots = dyadic_knots(c.knots, degree);
    ASSERT_EQ(f.knots.size(), c.knots.size() + 3);  // three spans, each halved
    const Eigen::SparseMatrix<double> t = refinement_matrix(c.knots, degree, f.knots);
    f.poles = t * c.poles;
    for (int i = 0; i <= 200; ++i) {
      const double s = i / 200.0;
      EXPECT_LT((f.evaluate(s) - c.evaluate(s)).norm(), 1e-13) << degree << " " << s;
    }
    const Eigen::VectorXd rows = t * Eigen::VectorXd::Ones(t.cols());  // partition of unity
    EXPECT_LT((rows.array() - 1.0).abs().maxCoeff(), 1e-14);
  }
  EXPECT_THROW(refinement_matrix(uniform_clamped_knots(3, 4), 3, uniform_clamped_knots(3, 3)),
               InvalidInput);
}

namespace {

// A base of 4 x 3 bicubic spans, a corner span refined twice and a middle span once.
HierarchicalSpace refined_space() {
  HierarchicalSpace h(SplineSpace::uniform(3, 3, 4, 3));
  h.refine(0, 0, 0);
  h.refine(0, 1, 0);
  h.refine(0, 2, 1);
  h.refine(1, 1, 1);
  return h;
}

// Random values: the exported finest surface equals the layers summed one by one, on a grid.
void expect_export_is_the_sum_of_layers(const HierarchicalSpace& h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> r(-1.0, 1.0);
  const Eigen::MatrixX3d values =
      Eigen::MatrixX3d::NullaryExpr(h.dof_count(), 3, [&] { return r(rng); });
  const Eigen::MatrixX3d finest = h.to_finest() * values;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 30; ++j) {
      const double u = i / 40.0, v = j / 30.0;
      const Eigen::Vector3d a = h.evaluate(values, u, v);
      const Eigen::Vector3d b = evaluate_surface(h.finest(), finest, u, v, 0).row(0).transpose();
      EXPECT_LT((a - b).norm(), 1e-12) << u << " " << v;
    }
}

}  // namespace

TEST(HierarchicalSpace, ExportEqualsTheSumOfLayers) {
  const HierarchicalSpace h = refined_space();
  ASSERT_EQ(h.levels(), 3);
  expect_export_is_the_sum_of_layers(h, 3);
}

TEST(HierarchicalSpace, DegreesOfFreedomAreIndependentAndNested) {
  const HierarchicalSpace h = refined_space();
  const Eigen::MatrixXd b = Eigen::MatrixXd(h.to_finest());
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(b, Eigen::ComputeThinU | Eigen::ComputeThinV);
  EXPECT_GT(svd.singularValues().minCoeff(), 1e-6);  // independent: an energy stays definite
  // Any surface of the base space lies in the refined one (refinement only adds).
  const SplineSpace base = h.layer(0);
  const Eigen::SparseMatrix<double> t0u =
      refinement_matrix(base.knots_u, 3, dyadic_knots(dyadic_knots(base.knots_u, 3), 3));
  const Eigen::SparseMatrix<double> t0v =
      refinement_matrix(base.knots_v, 3, dyadic_knots(dyadic_knots(base.knots_v, 3), 3));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> r(-1.0, 1.0);
  const Eigen::MatrixXd coarse =
      Eigen::MatrixXd::NullaryExpr(base.nu(), base.nv(), [&] { return r(rng); });
  const Eigen::MatrixXd fine2d = Eigen::MatrixXd(t0u) * coarse * Eigen::MatrixXd(t0v).transpose();
  Eigen::VectorXd fine(h.finest().size());
  for (int i = 0; i < h.finest().nu(); ++i)
    for (int j = 0; j < h.finest().nv(); ++j) fine(h.finest().index(i, j)) = fine2d(i, j);
  const Eigen::VectorXd x = svd.solve(fine);
  EXPECT_LT((b * x - fine).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(HierarchicalSpace, ALayerActsOnlyInsideItsRegion) {
  HierarchicalSpace h(SplineSpace::uniform(3, 3, 6, 6));
  EXPECT_EQ(h.refine_box(0, 0.4, 0.6, 0.4, 0.6), 4);  // the four middle spans
  const int base = h.layer(0).size();
  EXPECT_EQ(h.refine_box(0, 0.4, 0.6, 0.4, 0.6), 0);  // already refined
  // Level 1 has a 4 x 4-span region: (4 - 3) x (4 - 3) = 1 bicubic function inside it... plus
  // none at the border (the band held at zero); the base keeps the functions not wholly refined.
  int fine_dofs = 0;
  for (const HierarchicalDof& d : h.dofs()) fine_dofs += d.level == 1;
  EXPECT_EQ(fine_dofs, 1);
  EXPECT_EQ(h.dof_count(), base + fine_dofs);  // no base function lies wholly in 2 x 2 spans
  // That one function vanishes, with its derivatives, outside the refined square.
  Eigen::MatrixX3d values = Eigen::MatrixX3d::Zero(h.dof_count(), 3);
  for (size_t d = 0; d < h.dofs().size(); ++d)
    if (h.dofs()[d].level == 1) values(static_cast<Eigen::Index>(d), 2) = 1.0;
  const Eigen::MatrixX3d finest = h.to_finest() * values;
  for (double u : {0.1, 0.3, 1.0 / 3.0, 0.7, 0.95})
    for (double v : {0.05, 0.35, 0.5, 2.0 / 3.0, 0.9}) {
      const bool outside = u <= 1.0 / 3.0 || u >= 2.0 / 3.0 || v <= 1.0 / 3.0 || v >= 2.0 / 3.0;
      const Eigen::MatrixXd d = evaluate_surface(h.finest(), finest, u, v, 2);
      if (outside) {
        EXPECT_LT(d.col(2).cwiseAbs().maxCoeff(), 1e-12) << u << " " << v;
      }
    }
  EXPECT_GT(evaluate_surface(h.finest(), finest, 0.5, 0.5, 0)(0, 2), 0.1);
  EXPECT_THROW(h.refine(1, 0, 0), InvalidInput);  // not in level 1's region
  EXPECT_THROW(h.refine(0, 6, 0), InvalidInput);  // no such span
}

TEST(HierarchicalSpace, TheSumIsC2AcrossLayerBorders) {
  // Random values on a space refined twice over an L-shaped patch: the value and the first and
  // second derivatives agree on both sides of every layer border (cubic: C^2).
  HierarchicalSpace h(SplineSpace::uniform(3, 3, 6, 6));
  h.refine_box(0, 0.2, 0.8, 0.2, 0.5);
  h.refine_box(0, 0.2, 0.5, 0.5, 0.8);
  h.refine_box(1, 0.4, 0.6, 0.3, 0.45);
  ASSERT_EQ(h.levels(), 3);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> r(-1.0, 1.0);
  const Eigen::MatrixX3d values =
      Eigen::MatrixX3d::NullaryExpr(h.dof_count(), 3, [&] { return r(rng); });
  const Eigen::MatrixX3d poles = h.to_finest() * values;
  const double eps = 1e-10;  // a real jump would be of order one (second derivatives ~ 500)
  double jump3 = 0.0;
  // Borders of the level-1 region (u = 1/6, 5/6 lines of level 0's spans) and of level 2's.
  for (double u : {1.0 / 6.0, 5.0 / 6.0, 2.0 / 6.0 + 1.0 / 12.0})
    for (double v : {0.3, 0.4, 0.45}) {
      const Eigen::MatrixXd a = evaluate_surface(h.finest(), poles, u - eps, v, 2);
      const Eigen::MatrixXd b = evaluate_surface(h.finest(), poles, u + eps, v, 2);
      EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-5) << u << " " << v;  // C^2: 2 eps x third
      const Eigen::MatrixXd c = evaluate_surface(h.finest(), poles, u - 1e-3, v, 2);
      const Eigen::MatrixXd d = evaluate_surface(h.finest(), poles, u + 1e-3, v, 2);
      jump3 = std::max(jump3, (d.row(3) - c.row(3)).cwiseAbs().maxCoeff() / 2e-3);
    }
  EXPECT_GT(jump3, 1e-3);  // and not trivially smooth there: the third derivative is far from zero
}

namespace {

// Half a cylinder (rational along u) refined over a corner and then again inside it.
HierarchicalSpace refined_half_cylinder() {
  HierarchicalSpace h(test::half_cylinder_space());
  h.refine(0, 0, 1);
  h.refine(0, 1, 1);
  h.refine(1, 1, 2);
  return h;
}

// The weight function of a rational space at (u, v).
double weight_at(SplineSpace s, double u, double v) {
  Eigen::MatrixX3d w = Eigen::MatrixX3d::Zero(s.size(), 3);
  w.col(0) = s.weights;
  s.weights.resize(0);
  return evaluate_surface(s, w, u, v, 0)(0, 0);
}

}  // namespace

TEST(HierarchicalSpace, RationalLayersAddUpInHomogeneousCoordinates) {
  const HierarchicalSpace h = refined_half_cylinder();
  ASSERT_EQ(h.levels(), 3);
  ASSERT_TRUE(h.finest().rational());
  for (int i = 0; i <= 40; ++i)  // every layer carries the base's weight function exactly
    for (int j = 0; j <= 30; ++j)
      EXPECT_NEAR(weight_at(h.finest(), i / 40.0, j / 30.0),
                  weight_at(h.layer(0), i / 40.0, j / 30.0), 1e-14);
  expect_export_is_the_sum_of_layers(h, 13);
}

TEST(HierarchicalSpace, ARationalBaseStaysItselfWhenRefined) {
  const HierarchicalSpace h = refined_half_cylinder();
  const SplineSpace base = h.layer(0);
  const Eigen::MatrixX3d poles = test::half_cylinder_poles(base);
  const Eigen::MatrixX3d fine = h.base_to_finest(poles);
  for (int i = 0; i <= 50; ++i)
    for (int j = 0; j <= 20; ++j) {
      const double u = i / 50.0, v = j / 20.0;
      const Eigen::Vector3d p = evaluate_surface(h.finest(), fine, u, v, 0).row(0).transpose();
      EXPECT_NEAR(std::hypot(p(0), p(1)), 1.0, 1e-14) << u << " " << v;  // still the cylinder
      EXPECT_LT((p - evaluate_surface(base, poles, u, v, 0).row(0).transpose()).norm(), 1e-14);
    }
  // The refined space holds the cylinder, and its functions stay independent (a definite energy).
  const Eigen::MatrixXd b = Eigen::MatrixXd(h.to_finest());
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(b, Eigen::ComputeThinU | Eigen::ComputeThinV);
  EXPECT_GT(svd.singularValues().minCoeff(), 1e-6);
  const Eigen::MatrixX3d x = svd.solve(Eigen::MatrixXd(fine));
  EXPECT_LT((b * x - fine).cwiseAbs().maxCoeff(), 1e-12);
  // Unrefined, a point's values are the base's own poles.
  const HierarchicalSpace plain(base);
  EXPECT_LT((Eigen::MatrixXd(plain.to_finest()) * poles - poles).cwiseAbs().maxCoeff(), 1e-15);
}
