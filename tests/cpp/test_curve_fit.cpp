// SPDX-License-Identifier: LGPL-2.1-or-later
// The least-squares curve fit reproduces what its space holds and says when it is underdetermined.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "varsurf/core/curve_fit.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/knot_vector.hpp"

using namespace varsurf;

namespace {

Eigen::Vector3d cubic(double t) {
  return {1.0 + 2.0 * t - t * t * t, 3.0 * t * t - 0.5, std::pow(t - 0.3, 3)};
}

}  // namespace

TEST(CurveFit, ACubicOnAnyKnotsIsReproducedExactly) {
  // Samples at uneven parameters: the fit interpolates the ends and is exact inside.
  const std::vector<double> knots = {0, 0, 0, 0, 0.2, 0.45, 0.7, 1, 1, 1, 1};
  std::vector<double> t;
  for (int k = 0; k <= 40; ++k) t.push_back(std::pow(k / 40.0, 1.3));
  Eigen::MatrixXd points(static_cast<Eigen::Index>(t.size()), 3);
  for (size_t k = 0; k < t.size(); ++k) points.row(static_cast<Eigen::Index>(k)) = cubic(t[k]);
  const BSplineCurve c = fit_clamped_curve(t, points, 3, knots);
  EXPECT_EQ(c.pole_count(), 7);
  for (int k = 0; k <= 100; ++k) {
    const double s = k / 100.0;
    EXPECT_LE((c.evaluate(s) - cubic(s)).norm(), 1e-12) << s;
  }
}

TEST(CurveFit, AQuadraticSpaceFitsACubicInTheLeastSquaresSense) {
  // One span of degree 2 through a cubic's samples: the ends are held, the middle is the
  // least-squares pole, which has a closed form for y = t^3 at t = k/n (computed below).
  const std::vector<double> knots = {0, 0, 0, 1, 1, 1};
  const int n = 10;
  std::vector<double> t;
  Eigen::MatrixXd points(n + 1, 1);
  for (int k = 0; k <= n; ++k) {
    t.push_back(static_cast<double>(k) / n);
    points(k, 0) = std::pow(t.back(), 3);
  }
  const BSplineCurve c = fit_clamped_curve(t, points, 2, knots);
  // Minimise sum (B1(t) p + B2(t) - y)^2 over interior samples: p = sum B1 (y - B2) / sum B1^2.
  double num = 0.0, den = 0.0;
  for (int k = 1; k < n; ++k) {
    const double s = t[static_cast<size_t>(k)];
    const double b1 = 2.0 * s * (1.0 - s), b2 = s * s;
    num += b1 * (points(k, 0) - b2);
    den += b1 * b1;
  }
  EXPECT_NEAR(c.poles(0, 0), 0.0, 1e-15);
  EXPECT_NEAR(c.poles(2, 0), 1.0, 1e-15);
  EXPECT_NEAR(c.poles(1, 0), num / den, 1e-14);
}

TEST(CurveFit, FewerSamplesThanPolesIsASolveFailure) {
  const std::vector<double> knots = {0, 0, 0, 0, 0.5, 0.6, 1, 1, 1, 1};
  const std::vector<double> t = {0.0, 0.5, 1.0};  // one interior sample for four interior poles
  const Eigen::MatrixXd points = Eigen::MatrixXd::Random(3, 2);
  EXPECT_THROW(fit_clamped_curve(t, points, 3, knots), SolveFailure);
  EXPECT_THROW(fit_clamped_curve({0.0}, Eigen::MatrixXd::Zero(1, 2), 3, knots), InvalidInput);
}
