// SPDX-License-Identifier: LGPL-2.1-or-later
// The surface grid drawn while dragging: points and normals against the analytic surface.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "test_support.hpp"
#include "varsurf/core/errors.hpp"
#include "varsurf/core/surface_grid.hpp"

using namespace varsurf;

namespace {

// (u, v, u^2 v + v^3) lies in the bicubic space: fitted exactly.
Eigen::Vector3d f(double u, double v) {
  return {u, v, u * u * v + v * v * v};
}
Eigen::Vector3d unit_normal(double u, double v) {
  return Eigen::Vector3d(-2 * u * v, -(u * u + 3 * v * v), 1.0).normalized();
}

}  // namespace

TEST(SurfaceGrid, PointsAndNormalsOfAPolynomialSurface) {
  const SplineSpace space = SplineSpace::uniform(3, 3, 5, 4);
  const BSplineSurface s{space, varsurf::test::fit_poles(space, f)};
  const SurfaceGrid g = sample_grid(s, 7, 6);
  ASSERT_EQ(g.points.rows(), 8 * 7);
  for (int i = 0; i <= 7; ++i)
    for (int j = 0; j <= 6; ++j) {
      const double u = i / 7.0, v = j / 6.0;
      const Eigen::Index r = i * 7 + j;
      EXPECT_LT((g.points.row(r).transpose() - f(u, v)).norm(), 1e-12) << u << " " << v;
      EXPECT_LT((g.normals.row(r).transpose() - unit_normal(u, v)).norm(), 1e-12) << u << " " << v;
    }
}

TEST(SurfaceGrid, RationalPathAgreesWithUnitWeights) {
  SplineSpace space = SplineSpace::uniform(3, 2, 4, 3);
  const BSplineSurface plain{space, varsurf::test::fit_poles(space, f)};
  BSplineSurface rational = plain;
  rational.space.weights = Eigen::VectorXd::Ones(space.size());
  const SurfaceGrid a = sample_grid(plain, 5, 5), b = sample_grid(rational, 5, 5);
  EXPECT_LT((a.points - b.points).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((a.normals - b.normals).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(SurfaceGrid, RefusesBadSizes) {
  const SplineSpace space = SplineSpace::uniform(3, 3, 2, 2);
  const BSplineSurface s{space, varsurf::test::fit_poles(space, f)};
  EXPECT_THROW(sample_grid(s, 0, 4), InvalidInput);
  EXPECT_THROW(sample_grid(s, 4, 5000), InvalidInput);
  BSplineSurface broken = s;
  broken.poles.resize(3, 3);
  EXPECT_THROW(sample_grid(broken, 4, 4), InvalidInput);
}
