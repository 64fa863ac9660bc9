// SPDX-License-Identifier: LGPL-2.1-or-later
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"
#include "varsurf/core/spline_space.hpp"

using namespace varsurf;

namespace {

// Quarter cylinder of radius r (rational quadratic in u, linear in v): every point lies at
// distance r from the z axis.
BSplineSurface quarter_cylinder(double r, double height) {
  BSplineSurface s;
  s.space.degree_u = 2;
  s.space.degree_v = 1;
  s.space.knots_u = {0, 0, 0, 1, 1, 1};
  s.space.knots_v = {0, 0, 1, 1};
  const double w = std::sqrt(0.5);
  s.space.weights.resize(6);
  s.poles.resize(6, 3);
  const Eigen::Vector3d ring[3] = {{r, 0, 0}, {r, r, 0}, {0, r, 0}};
  const double ws[3] = {1.0, w, 1.0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 2; ++j) {
      const int k = s.space.index(i, j);
      s.poles.row(k) = (ring[i] + Eigen::Vector3d(0, 0, j * height)).transpose();
      s.space.weights(k) = ws[i];
    }
  return s;
}

}  // namespace

TEST(SplineSpace, RationalCylinderIsExact) {
  const BSplineSurface s = quarter_cylinder(2.5, 4.0);
  ASSERT_NO_THROW(s.validate());
  for (double u = 0.0; u <= 1.0; u += 0.05)
    for (double v : {0.0, 0.3, 1.0}) {
      const Eigen::Vector3d p = s.evaluate(u, v);
      EXPECT_NEAR(std::hypot(p.x(), p.y()), 2.5, 1e-13);
      EXPECT_NEAR(p.z(), 4.0 * v, 1e-13);
    }
}

TEST(SplineSpace, RationalDerivativesMatchFiniteDifferences) {
  BSplineSurface s = quarter_cylinder(1.0, 1.0);
  const double h = 1e-5;
  for (double u : {0.2, 0.5, 0.8})
    for (double v : {0.25, 0.6}) {
      const Eigen::MatrixXd d = evaluate_surface(s.space, s.poles, u, v, 2);
      const Eigen::MatrixXd pu = evaluate_surface(s.space, s.poles, u + h, v, 2);
      const Eigen::MatrixXd mu = evaluate_surface(s.space, s.poles, u - h, v, 2);
      const Eigen::MatrixXd pv = evaluate_surface(s.space, s.poles, u, v + h, 2);
      const Eigen::MatrixXd mv = evaluate_surface(s.space, s.poles, u, v - h, 2);
      EXPECT_LT((d.row(1) - (pu.row(0) - mu.row(0)) / (2 * h)).norm(), 1e-8);
      EXPECT_LT((d.row(2) - (pv.row(0) - mv.row(0)) / (2 * h)).norm(), 1e-8);
      EXPECT_LT((d.row(3) - (pu.row(1) - mu.row(1)) / (2 * h)).norm(), 1e-6);
      EXPECT_LT((d.row(4) - (pv.row(1) - mv.row(1)) / (2 * h)).norm(), 1e-6);
      EXPECT_LT((d.row(5) - (pv.row(2) - mv.row(2)) / (2 * h)).norm(), 1e-6);
      // On a cylinder about z: the u-derivative is tangent to the circle.
      EXPECT_NEAR(d.row(0).head(2).dot(d.row(1).head(2)), 0.0, 1e-12);
    }
}

TEST(SplineSpace, BasisIsPartitionOfUnity) {
  SplineSpace sp = SplineSpace::uniform(3, 2, 5, 3);
  sp.knots_u = {0, 0, 0, 0, 0.1, 0.2, 0.7, 0.8, 1, 1, 1, 1};
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  sp.weights = Eigen::VectorXd::Ones(sp.size());
  for (int k = 0; k < sp.size(); ++k) sp.weights(k) = 0.5 + uni(rng);
  ASSERT_NO_THROW(sp.validate());
  for (int i = 0; i < 50; ++i) {
    const BasisSample s = sp.basis(uni(rng), uni(rng), 2);
    EXPECT_NEAR(s.values.row(0).sum(), 1.0, 1e-13);
    for (int d = 1; d < 6; ++d) EXPECT_NEAR(s.values.row(d).sum(), 0.0, 1e-9);
  }
}

TEST(SplineSpace, PolynomialSurfacesAreReproduced) {
  SplineSpace sp = SplineSpace::uniform(3, 3, 4, 5);
  sp.knots_v = {0, 0, 0, 0, 0.15, 0.3, 0.55, 0.8, 1, 1, 1, 1};
  auto f = [](double u, double v) {
    return Eigen::Vector3d(u * u * v - 2 * v, 3 * u * v * v * v + u, std::pow(u, 3) - v * v);
  };
  const Eigen::MatrixX3d poles = test::fit_poles(sp, f);
  for (double u = 0.0; u <= 1.0; u += 0.1)
    for (double v = 0.0; v <= 1.0; v += 0.1)
      EXPECT_LT((evaluate_surface(sp, poles, u, v, 0).row(0).transpose() - f(u, v)).norm(), 1e-12);
}

TEST(SplineSpace, BoundaryIndices) {
  const SplineSpace sp = SplineSpace::uniform(2, 3, 3, 2);  // 5 x 5 poles
  const std::vector<int> b = boundary_pole_indices(sp);
  EXPECT_EQ(b.size(), 16u);
  for (int k : b) {
    const int i = k / sp.nv(), j = k % sp.nv();
    EXPECT_TRUE(i == 0 || j == 0 || i == sp.nu() - 1 || j == sp.nv() - 1);
  }
}

TEST(SplineSpace, RejectsInconsistentData) {
  SplineSpace sp = SplineSpace::uniform(3, 3, 2, 2);
  sp.weights = Eigen::VectorXd::Ones(3);
  EXPECT_THROW(sp.validate(), InvalidInput);
  sp.weights = -Eigen::VectorXd::Ones(sp.size());
  EXPECT_THROW(sp.validate(), InvalidInput);
  BSplineSurface s;
  s.space = SplineSpace::uniform(3, 3, 2, 2);
  s.poles = Eigen::MatrixX3d::Zero(s.space.size(), 3);
  s.poles(3, 1) = NAN;
  EXPECT_THROW(s.validate(), InvalidInput);
  EXPECT_THROW(s.space.basis(0.5, 0.5, 3), InvalidInput);
}

// Finite poles beyond +-1e12 overflow when evaluated (a 1e308 sheet made a deviation search run
// for minutes): validate() refuses them; poles at the limit pass.
TEST(SplineSpace, RefusesHugePoles) {
  const SplineSpace space = SplineSpace::uniform(3, 3, 2, 2);
  Eigen::MatrixX3d poles = Eigen::MatrixX3d::Zero(space.size(), 3);
  poles(7, 2) = kMaxCoordinate;
  EXPECT_NO_THROW((BSplineSurface{space, poles}.validate()));
  poles(7, 2) = -1e13;
  EXPECT_THROW((BSplineSurface{space, poles}.validate()), InvalidInput);
  poles(7, 2) = 1e308;
  EXPECT_THROW((BSplineSurface{space, poles}.validate()), InvalidInput);
  EXPECT_THROW(SplineSpace::uniform(3, 3, 2147483647, 2), InvalidInput);
}

// The allocation-free tensor contraction agrees with the basis functions summed one by one, for
// odd and even degrees on non-uniform knots, every derivative row, and a degree beyond the stack
// buffers (its work arrays on the heap).
TEST(SplineSpace, EvaluationEqualsTheSumOverTheBasis) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0);
  for (auto [pu, pv] : {std::pair{3, 3}, std::pair{2, 5}, std::pair{1, 4}, std::pair{17, 2}}) {
    BSplineSurface s;
    s.space.degree_u = pu;
    s.space.degree_v = pv;
    s.space.knots_u = uniform_clamped_knots(pu, 4, -2.0, 3.0);
    s.space.knots_v = uniform_clamped_knots(pv, 3, 0.0, 0.7);
    s.space.knots_u[static_cast<size_t>(pu + 1)] -= 0.4;  // non-uniform
    s.poles.resize(s.space.size(), 3);
    for (int k = 0; k < s.poles.size(); ++k) s.poles.data()[k] = coordinate(rng);
    std::uniform_real_distribution<double> u(-2.0, 3.0), v(0.0, 0.7);
    for (int trial = 0; trial < 50; ++trial) {
      const double a = trial == 0 ? 3.0 : u(rng), b = trial == 0 ? 0.0 : v(rng);
      const Eigen::MatrixXd fast = evaluate_surface(s.space, s.poles, a, b, 2);
      const BasisSample basis = s.space.basis(a, b, 2);
      Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(6, 3);
      for (size_t k = 0; k < basis.index.size(); ++k)
        sum += basis.values.col(static_cast<Eigen::Index>(k)) * s.poles.row(basis.index[k]);
      const double scale = 1.0 + sum.cwiseAbs().maxCoeff();
      EXPECT_LT((fast - sum).cwiseAbs().maxCoeff(), 1e-12 * scale) << pu << " " << pv;
      EXPECT_LT((evaluate_surface(s.space, s.poles, a, b, 0).row(0) - sum.row(0)).norm(),
                1e-12 * scale);
    }
  }
}
